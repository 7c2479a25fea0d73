#pragma once
// Two independent jobs at once (the supine and the prone scan's work), with one progress and
// prompt cancellation. The host's sink is only ever called from the calling thread: the second
// job runs on a worker thread whose progress is stored atomically and forwarded (with the first
// job's, as their mean) by the caller, which also polls while it waits. When the host cancels,
// the worker is asked to stop at its next Report(), both are joined, and Cancelled propagates.
// An exception of either job is rethrown in the caller after both have ended (the first job's
// first).
#include "Core/Cancel.h"

#include <atomic>
#include <chrono>
#include <exception>
#include <future>
#include <thread>

namespace colonmap {

template <class First, class Second>
void RunConcurrently(First&& first, Second&& second, ProgressSink& progress) {
  std::atomic<double> secondFraction{0.0};
  std::atomic<bool> stop{false};
  double firstFraction = 0.0;
  struct WorkerSink : ProgressSink {
    std::atomic<double>& fraction;
    std::atomic<bool>& stop;
    WorkerSink(std::atomic<double>& f, std::atomic<bool>& s) : fraction(f), stop(s) {}
    void Report(double f) override {
      fraction.store(f);
      if (stop.load()) throw Cancelled();
    }
  } workerSink(secondFraction, stop);
  struct CallerSink : ProgressSink {
    ProgressSink& parent;
    double& own;
    std::atomic<double>& other;
    std::atomic<bool>& stop;
    CallerSink(ProgressSink& p, double& o, std::atomic<double>& w, std::atomic<bool>& s)
        : parent(p), own(o), other(w), stop(s) {}
    void Report(double f) override {
      own = f;
      try {
        parent.Report(0.5 * (own + other.load()));
      } catch (const Cancelled&) {
        stop.store(true);
        throw;
      }
    }
  } callerSink(progress, firstFraction, secondFraction, stop);

  std::future<void> worker = std::async(std::launch::async, [&] { second(static_cast<ProgressSink&>(workerSink)); });
  std::exception_ptr firstError;
  try {
    first(static_cast<ProgressSink&>(callerSink));
    callerSink.Report(1.0);
    // Keep the host informed (and able to cancel) while the worker finishes.
    while (worker.wait_for(std::chrono::milliseconds(100)) != std::future_status::ready) callerSink.Report(1.0);
  } catch (...) {
    firstError = std::current_exception();
    stop.store(true);
  }
  std::exception_ptr secondError;
  try {
    worker.get();
  } catch (...) {
    secondError = std::current_exception();
  }
  if (firstError) std::rethrow_exception(firstError);
  if (secondError) std::rethrow_exception(secondError);
}

}  // namespace colonmap
