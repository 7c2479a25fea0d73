#include "CLI/CpuTime.h"

#include <gtest/gtest.h>

#include <ctime>
#include <thread>
#include <vector>

namespace {

// Busy until this thread itself has used `seconds` of CPU (whatever else the machine runs).
void SpinFor(double seconds) {
  const auto threadCpu = [] {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
  };
  const double start = threadCpu();
  volatile double sink = 0.0;
  while (threadCpu() - start < seconds)
    for (int i = 0; i < 10000; ++i) sink = sink + 1e-9 * i;
}

}  // namespace

TEST(CpuTime, CountsTheCpuOfEveryThreadOfTheProcess) {
  // Two threads each using 0.2 s of CPU: the process used at least 0.4 s, however the cores were
  // shared, which a wall clock or a per-thread clock would not show.
  const double before = colonmap::cli::ProcessCpuSeconds();
  std::vector<std::thread> threads;
  for (int t = 0; t < 2; ++t) threads.emplace_back(SpinFor, 0.2);
  for (auto& t : threads) t.join();
  const double used = colonmap::cli::ProcessCpuSeconds() - before;
  EXPECT_GE(used, 0.4 - 0.02);  // getrusage's tick granularity
  EXPECT_LT(used, 5.0);
}
