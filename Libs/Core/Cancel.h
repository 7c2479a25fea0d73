#pragma once
// Cooperative cancellation and progress for long computations in Libs. A module passes a
// ProgressSink; Libs code calls Report() now and then (at least every 0.2 s of work) and stops
// by throwing Cancelled when the host asked to abort.
#include <algorithm>
#include <stdexcept>
#include <string>

namespace colonmap {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("cancelled by the host") {}
};

class ProgressSink {
 public:
  virtual ~ProgressSink() = default;
  // fraction in [0,1] of the current stage. Throws Cancelled when the host aborted.
  virtual void Report(double fraction) = 0;
};

// Maps a sub-step onto the range [from, to] of a parent's progress (several steps in one stage).
class SubProgress : public ProgressSink {
 public:
  SubProgress(ProgressSink& parent, double from, double to) : parent_(parent), from_(from), to_(to) {}
  void Report(double fraction) override {
    parent_.Report(from_ + (to_ - from_) * std::clamp(fraction, 0.0, 1.0));
  }

 private:
  ProgressSink& parent_;
  double from_, to_;
};

// A sink that ignores progress and never cancels, for tests and batch code.
class NullProgress : public ProgressSink {
 public:
  void Report(double) override {}
};

}  // namespace colonmap
