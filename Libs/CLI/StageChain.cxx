#include "CLI/StageChain.h"

#include "CLI/CpuTime.h"
#include "Core/Cancel.h"

#include <algorithm>
#include <chrono>

namespace colonmap::cli {

StageChain::StageChain(ProgressSink& sink, std::vector<std::pair<std::string, double>> plan,
                       std::function<bool()> hostAbort, VolumeShelf* shelf)
    : sink_(sink), hostAbort_(std::move(hostAbort)), shelf_(shelf), plan_(std::move(plan)) {}

std::map<std::string, std::string> StageChain::Run(const std::string& step, const char* moduleName, const char* xml,
                                                   ModuleBody body, const std::vector<std::string>& arguments) {
  if (AbortRequested()) throw Cancelled();  // between steps too: the last one may have ended in a long write
  // Steps run in the plan's order: each takes its share after the one before.
  double total = 0.0, weight = 0.0;
  for (const auto& [name, w] : plan_) {
    total += w;
    if (name == step) weight = w;
  }
  from_ = to_;
  to_ = total > 0 ? from_ + weight / total : from_;
  Report(0.0);
  StepRecord record{step, moduleName, 0.0, 0.0, {}};
  const auto start = std::chrono::steady_clock::now();
  const double cpuStart = ThreadCpuSeconds();
  record.results = RunNestedModule(*this, moduleName, xml, body, arguments, shelf_);
  record.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  record.threadCpuSeconds = ThreadCpuSeconds() - cpuStart;
  Report(1.0);
  records_.push_back(std::move(record));
  return records_.back().results;
}

void StageChain::Report(double fraction) {
  last_ = from_ + (to_ - from_) * std::clamp(fraction, 0.0, 1.0);
  sink_.Report(last_);
}

bool StageChain::AbortRequested() const {
  if (hostAbort_ && hostAbort_()) return true;
  sink_.Report(last_);
  return false;
}

void StageChain::Note(const std::string& text) {
  const std::lock_guard<std::mutex> lock(notesMutex_);
  notes_.push_back(text);
}

std::vector<std::string> StageChain::TakeNotes() {
  const std::lock_guard<std::mutex> lock(notesMutex_);
  std::vector<std::string> out;
  out.swap(notes_);
  return out;
}

}  // namespace colonmap::cli
