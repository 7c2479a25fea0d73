#pragma once
// Progress of a module run, reported the way the host understands it:
//  - Slicer running the program: <filter-start>/<filter-progress>/<filter-end> tags on stdout,
//    one per line, flushed;
//  - a person at a terminal: readable lines with stage names and times instead;
//  - Slicer running the library in-process: the ModuleProcessInformation struct and its callback;
//  - a module run as one stage of another (ColonSupineProne): overall progress goes to the
//    parent's current stage, notes to the parent, and the parent's Abort applies.
// Report() also polls the host's Abort flag and throws colonmap::Cancelled when it is set.
#include "CLI/ProcessInformation.h"
#include "Core/Cancel.h"

#include <chrono>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::cli {

// What a nested module's progress reports into (RunNestedModule): the fraction of a stage, its
// notes, and whether the host asked to stop. A Progress is one; a job of a pipeline run on its
// own thread (CLI/StageChain.h) has another.
class ProgressParent : public ProgressSink {
 public:
  virtual void Note(const std::string& text) = 0;
  virtual bool AbortRequested() const = 0;
};

class Progress : public ProgressParent {
 public:
  enum class Style { SlicerTags, Terminal, Silent };

  Progress(std::string moduleName, Style style, ModuleProcessInformation* info, std::FILE* out);
  // Nested: reports into `parent`'s current stage.
  Progress(std::string moduleName, ProgressParent& parent);

  // Declares the stages of the run with their relative weights, so that overall progress rises
  // evenly. Optional: undeclared stages share what is left.
  void Plan(std::vector<std::pair<std::string, double>> stages);

  void StartStage(const std::string& name, const std::string& comment = std::string());
  void Report(double fraction) override;  // fraction of the current stage
  void EndStage();
  void Finish();                         // overall progress 1, final callback

  // Seconds per finished stage, in order.
  const std::vector<std::pair<std::string, double>>& StageTimes() const { return times_; }
  // The host sets Abort from its own thread (and ColonSupineProne's jobs read it from two): an
  // atomic read of the plain field.
  bool AbortRequested() const override {
    return parent_ ? parent_->AbortRequested() : info_ && __atomic_load_n(&info_->Abort, __ATOMIC_RELAXED);
  }
  // Prints a note (never to stderr: Slicer logs stderr as errors).
  void Note(const std::string& text) override;

 private:
  double Now() const;
  void Publish(double stageFraction, bool force);
  double StageWeight(const std::string& name) const;

  std::string module_;
  Style style_;
  ModuleProcessInformation* info_;
  std::FILE* out_;
  ProgressParent* parent_ = nullptr;
  std::vector<std::pair<std::string, double>> plan_;
  std::vector<std::pair<std::string, double>> times_;
  std::string stage_;
  double stageStart_ = 0.0;
  double doneWeight_ = 0.0;      // weights of finished stages
  double currentWeight_ = 0.0;
  double lastPublished_ = -1.0;
  double lastPublishTime_ = -1.0;
  double lastOverall_ = 0.0;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace colonmap::cli
