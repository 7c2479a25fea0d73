#pragma once
// Two independent jobs at once (the supine and the prone scan's work; the flat and the
// endoluminal views), with one progress and prompt cancellation. The host's sink is only ever
// called from the calling thread: the second
// job runs on a worker thread whose progress is stored atomically and forwarded (with the first
// job's, as their mean) by the caller, which also polls while it waits. When the host cancels,
// the worker is asked to stop at its next Report(), both are joined, and Cancelled propagates.
// When the worker fails, the first job is stopped the same way at its next Report() (its work
// is wasted), and the worker's error is what propagates. Otherwise an exception of either job is
// rethrown in the caller after both have ended (the first job's first).
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
  std::atomic<bool> stop{false}, secondFailed{false};
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
    std::atomic<bool>& otherFailed;
    CallerSink(ProgressSink& p, double& o, std::atomic<double>& w, std::atomic<bool>& s, std::atomic<bool>& failed)
        : parent(p), own(o), other(w), stop(s), otherFailed(failed) {}
    void Report(double f) override {
      if (otherFailed.load()) throw Cancelled();  // stopped for the worker's error, rethrown below
      own = f;
      try {
        parent.Report(0.5 * (own + other.load()));
      } catch (const Cancelled&) {
        stop.store(true);
        throw;
      }
    }
  } callerSink(progress, firstFraction, secondFraction, stop, secondFailed);

  std::future<void> worker = std::async(std::launch::async, [&] {
    try {
      second(static_cast<ProgressSink&>(workerSink));
    } catch (const Cancelled&) {
      throw;
    } catch (...) {
      secondFailed.store(true);
      throw;
    }
  });
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
  if (secondFailed.load() && secondError) {
    // The first job's error may only be the stop the worker's failure caused.
    bool firstCancelled = !firstError;
    if (firstError) {
      try {
        std::rethrow_exception(firstError);
      } catch (const Cancelled&) {
        firstCancelled = true;
      } catch (...) {
      }
    }
    if (firstCancelled) std::rethrow_exception(secondError);
  }
  if (firstError) std::rethrow_exception(firstError);
  if (secondError) std::rethrow_exception(secondError);
  progress.Report(1.0);  // both done (the last report may have been before the worker's end)
}

}  // namespace colonmap
