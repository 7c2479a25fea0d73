#include "CLI/Progress.h"

#include "CLI/Format.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

namespace colonmap::cli {

ModuleProcessInformation* ProcessInformationFromAddress(const char* address) {
  if (!address || !*address) return nullptr;
  char* end = nullptr;
  const unsigned long long value = std::strtoull(address, &end, 16);
  if (!end || *end != '\0' || value == 0) return nullptr;
  return reinterpret_cast<ModuleProcessInformation*>(static_cast<std::uintptr_t>(value));
}

Progress::Progress(std::string moduleName, Style style, ModuleProcessInformation* info, std::FILE* out)
    : module_(std::move(moduleName)), style_(style), info_(info), out_(out),
      start_(std::chrono::steady_clock::now()) {
  if (info_) {
    info_->Progress = 0.0f;
    info_->StageProgress = 0.0f;
    info_->ElapsedTime = 0.0;
    info_->ProgressMessage[0] = '\0';
  }
}

Progress::Progress(std::string moduleName, ProgressParent& parent)
    : module_(std::move(moduleName)), style_(Style::Silent), info_(nullptr), out_(nullptr), parent_(&parent),
      start_(std::chrono::steady_clock::now()) {}

void Progress::Plan(std::vector<std::pair<std::string, double>> stages) { plan_ = std::move(stages); }

double Progress::Now() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

double Progress::StageWeight(const std::string& name) const {
  double total = 0.0, weight = 0.0;
  for (const auto& s : plan_) {
    total += s.second;
    if (s.first == name) weight = s.second;
  }
  return total > 0.0 ? weight / total : 0.0;
}

void Progress::StartStage(const std::string& name, const std::string& comment) {
  // A new stage is a poll of Cancel too: the last one may have ended in a long write.
  if (AbortRequested()) throw Cancelled();
  stage_ = name;
  stageStart_ = Now();
  currentWeight_ = StageWeight(name);
  lastPublished_ = -1.0;
  if (style_ == Style::SlicerTags) {
    std::fprintf(out_, "<filter-start><filter-name>%s</filter-name><filter-comment>%s</filter-comment></filter-start>\n",
                 name.c_str(), (comment.empty() ? name : comment).c_str());
  } else if (style_ == Style::Terminal) {
    std::fprintf(out_, "%s: %s%s\n", module_.c_str(), name.c_str(), comment.empty() ? "" : (" - " + comment).c_str());
  }
  if (out_) std::fflush(out_);
  if (info_) {
    std::strncpy(info_->ProgressMessage, name.c_str(), sizeof(info_->ProgressMessage) - 1);
    info_->ProgressMessage[sizeof(info_->ProgressMessage) - 1] = '\0';
  }
  Publish(0.0, true);
}

void Progress::Publish(double stageFraction, bool force) {
  stageFraction = std::clamp(stageFraction, 0.0, 1.0);
  const double now = Now();
  if (!force && stageFraction - lastPublished_ < 0.01 && now - lastPublishTime_ < 0.5) return;
  lastPublished_ = stageFraction;
  lastPublishTime_ = now;
  // Without a plan each stage runs the bar from 0 to 1, as most Slicer CLIs do.
  double overall = plan_.empty() ? stageFraction : doneWeight_ + currentWeight_ * stageFraction;
  if (!plan_.empty()) overall = std::max(overall, lastOverall_);
  lastOverall_ = overall;
  if (parent_) parent_->Report(overall);
  if (style_ == Style::SlicerTags) {
    std::fprintf(out_, "<filter-progress>%s</filter-progress>\n", FormatFixed(overall, 4).c_str());
    std::fprintf(out_, "<filter-stage-progress>%s</filter-stage-progress>\n", FormatFixed(stageFraction, 4).c_str());
    std::fflush(out_);
  }
  if (info_) {
    info_->Progress = static_cast<float>(overall);
    info_->StageProgress = static_cast<float>(stageFraction);
    info_->ElapsedTime = now;
    if (info_->ProgressCallbackFunction) info_->ProgressCallbackFunction(info_->ProgressCallbackClientData);
  }
}

void Progress::Report(double fraction) {
  if (AbortRequested()) throw Cancelled();
  Publish(fraction, false);
}

void Progress::EndStage() {
  if (stage_.empty()) return;
  Publish(1.0, true);
  const double seconds = Now() - stageStart_;
  times_.emplace_back(stage_, seconds);
  doneWeight_ += currentWeight_;
  if (style_ == Style::SlicerTags) {
    std::fprintf(out_, "<filter-end><filter-name>%s</filter-name><filter-time>%s</filter-time></filter-end>\n",
                 stage_.c_str(), FormatFixed(seconds, 3).c_str());
  } else if (style_ == Style::Terminal) {
    std::fprintf(out_, "%s: %s done in %s s\n", module_.c_str(), stage_.c_str(), FormatFixed(seconds, 2).c_str());
  }
  if (out_) std::fflush(out_);
  stage_.clear();
}

void Progress::Finish() {
  if (!stage_.empty()) EndStage();
  lastOverall_ = 1.0;
  if (parent_) parent_->Report(1.0);
  if (style_ == Style::SlicerTags) {
    std::fprintf(out_, "<filter-progress>1</filter-progress>\n");
    std::fflush(out_);
  }
  if (info_) {
    info_->Progress = 1.0f;
    info_->StageProgress = 1.0f;
    info_->ElapsedTime = Now();
    if (info_->ProgressCallbackFunction) info_->ProgressCallbackFunction(info_->ProgressCallbackClientData);
  }
}

void Progress::Note(const std::string& text) {
  if (parent_) return parent_->Note(text);
  if (!out_ || style_ == Style::Silent) return;
  std::fprintf(out_, "%s\n", text.c_str());
  std::fflush(out_);
}

}  // namespace colonmap::cli
