#pragma once
// One scan's stages of a pipeline run as a job of their own (issue 22: ColonSupineProne runs the
// supine and the prone scan's cleansing, segmentation and surface side by side with
// Core/RunConcurrently.h). The chain runs nested modules one after the other on whichever thread
// calls it: each step's progress fills its share of the job's ProgressSink, the host's Abort
// reaches it directly (hostAbort) and through that sink (RunConcurrently's sinks throw Cancelled
// when the other job stopped or failed), its notes are kept for the caller to print from the
// host's thread, and each step leaves a record.
#include "CLI/ModuleRunner.h"

#include <functional>
#include <map>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::cli {

struct StepRecord {
  std::string name;    // e.g. "surface prone"
  std::string module;  // e.g. "ColonSurface"
  double seconds = 0.0;           // wall time of the step
  double threadCpuSeconds = 0.0;  // CPU time of the chain's own thread during the step (not the
                                  // toolkits' worker threads)
  std::map<std::string, std::string> results;  // the module's return parameters
};

class StageChain : public ProgressParent {
 public:
  // plan: the steps' names and relative weights, in the order they run (a step not named shares
  // nothing).
  // hostAbort (optional): the host's Abort, read directly so that a job on a worker thread stops
  // as soon as the one on the host's thread, not after it.
  // shelf (optional): the pipeline's volumes handed on in memory (Core/VolumeShelf.h).
  StageChain(ProgressSink& sink, std::vector<std::pair<std::string, double>> plan,
             std::function<bool()> hostAbort = {}, VolumeShelf* shelf = nullptr);

  // Runs a module's body as the next step (RunNestedModule); its record is appended.
  std::map<std::string, std::string> Run(const std::string& step, const char* moduleName, const char* xml,
                                         ModuleBody body, const std::vector<std::string>& arguments);

  void Report(double fraction) override;  // fraction of the current step
  void Note(const std::string& text) override;
  // The host's Abort, then a poll of the job's sink with the current fraction: RunConcurrently's
  // sinks (and a Progress) throw Cancelled when the run was stopped. A nested Progress asks this
  // on every Report, while it passes fractions on at most every 0.5 s: so Cancel is seen at once.
  bool AbortRequested() const override;

  const std::vector<StepRecord>& Records() const { return records_; }
  std::vector<std::string> TakeNotes();

 private:
  ProgressSink& sink_;
  std::function<bool()> hostAbort_;
  VolumeShelf* shelf_;
  std::vector<std::pair<std::string, double>> plan_;
  double from_ = 0.0, to_ = 0.0;  // the current step's share of the job
  double last_ = 0.0;             // the last fraction of the job passed on
  std::vector<StepRecord> records_;
  std::mutex notesMutex_;  // notes come from the job's thread; the lock keeps a module that
                           // notes from a thread of its own safe too
  std::vector<std::string> notes_;
};

}  // namespace colonmap::cli
