#pragma once
// A progress sink for tests: it keeps every fraction reported and, given cancelAt > 0, throws
// Cancelled at that report (a host that cancels at a known point).
#include "Core/Cancel.h"

#include <vector>

namespace colonmap {

class RecordingProgress : public ProgressSink {
 public:
  explicit RecordingProgress(int cancelAt = 0) : cancelAt_(cancelAt) {}
  void Report(double fraction) override {
    fractions.push_back(fraction);
    if (static_cast<int>(fractions.size()) == cancelAt_) throw Cancelled();
  }
  std::vector<double> fractions;  // every report, the cancelling one included

 private:
  int cancelAt_;
};

}  // namespace colonmap
