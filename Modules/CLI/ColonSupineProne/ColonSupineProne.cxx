// ColonSupineProne: the whole pipeline in one module (issue 9, DESIGN §2.0). Runs the stage
// modules in this process (cli::RunNestedModule: each parses its own arguments, reports into
// one stage of this run and commits into its stage folder), then writes summary.json and
// report.html. Stage folders are hidden temporaries until the very end, so a failed or
// cancelled run leaves nothing.
#include "CLI/CpuTime.h"
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "CLI/StageChain.h"
#include "Core/Error.h"
#include "Core/RunConcurrently.h"
#include "Core/VolumeShelf.h"
#include "IO/ImageCheck.h"
#include "IO/MarkupsIO.h"
#include "IO/NodeFiles.h"
#include "IO/StageReports.h"
#include "IO/ToolkitThreads.h"
#include "Report/PipelineReport.h"
#include "Report/QualityFlags.h"

#include <nlohmann/json.hpp>

#include <array>
#include <chrono>
#include <filesystem>
#include <optional>
#include <regex>
#include <set>
#include <tuple>

COLONMAP_DECLARE_MODULE(ColonCleansing)
COLONMAP_DECLARE_MODULE(ColonSegmentation)
COLONMAP_DECLARE_MODULE(ColonSurface)
COLONMAP_DECLARE_MODULE(ColonLandmarks)
COLONMAP_DECLARE_MODULE(ColonFlattening)
COLONMAP_DECLARE_MODULE(ColonRegistration)
COLONMAP_DECLARE_MODULE(ColonTransferPoints)
COLONMAP_DECLARE_MODULE(ColonEvaluateRegistration)
COLONMAP_DECLARE_MODULE(ColonFlatViews)
COLONMAP_DECLARE_MODULE(ColonEndoluminalViews)

namespace {

using namespace colonmap;
using nlohmann::json;
namespace fs = std::filesystem;

struct StageModule {
  const char* name;
  const char* xml;
  cli::ModuleBody body;
};
#define COLONMAP_STAGE(Name) \
  StageModule { #Name, colonmap::modules::Name##XML, &colonmap::modules::Run##Name }

const char* const kScans[2] = {"supine", "prone"};
// The host's progress stages that run two jobs side by side (Pipeline::RunBoth).
const char* const kScansStage = "scans: cleansing, segmentation, surface";
const char* const kLabelMapsStage = "scans: surface";  // --labelMaps: no cleansing, no segmentation
const char* const kFlatteningStage = "flattening of both scans";
const char* const kViewsStage = "views: flat and endoluminal";  // the two views modules side by side

struct Options {
  std::string scan[2], out, findings, truth, method, targetFaces, labelValue;
  bool labelMaps = false, views = true;
  bool sideBySide = true;  // the two scans' independent stages on two threads (--sequential: off)
};

// A module's return parameters as a stage record's "results".
json ResultsJson(const std::map<std::string, std::string>& results) {
  json r = json::object();
  for (const auto& [k, v] : results) r[k] = v;
  return r;
}

// Whether the run renders endoluminal views: findings to look at, views wanted, CTs to render.
bool EndoluminalViews(const Options& o) { return !o.findings.empty() && o.views && !o.labelMaps; }

// Relative weights of a scan's steps in the host's progress (a block's is its steps' sum).
constexpr double kCleansingWeight = 2.0, kSegmentationWeight = 5.0, kSurfaceWeight = 9.0, kFlatteningWeight = 1.0;
constexpr double kFlatViewsWeight = 1.0, kEndoluminalViewsWeight = 2.0;

// One step of a job (RunBoth): a stage record's name, the module, its arguments. An optional
// step that fails (colonmap::Error, e.g. no X display to render with) does not stop the run: its
// message is kept (Pipeline::Failure) and the job goes on.
struct Step {
  std::string name;
  StageModule module;
  std::vector<std::string> args;
  double weight;
  bool optional = false;
};

// The run's wall seconds from its records: the stages run alone plus the blocks of jobs side by
// side (a stage of a block the records do not give counts on its own). The whole run and
// --reportOnly both count with this, so their summaries agree to the last bit.
double WallSeconds(const json& stages, const json& blocks) {
  double total = 0.0;
  std::set<std::string> blockNames;
  for (const auto& b : blocks)
    if (b.is_object() && b.value("seconds", json()).is_number()) {
      total += b["seconds"].get<double>();
      blockNames.insert(b.value("name", std::string()));
    }
  for (const auto& s : stages)
    if (s.is_object() && s.value("seconds", json()).is_number() &&
        !(s.contains("block") && s["block"].is_string() && blockNames.count(s["block"].get<std::string>())))
      total += s["seconds"].get<double>();
  return total;
}

// One run of the pipeline: stage folders (temporary until the end), stage records.
class Pipeline {
 public:
  Pipeline(cli::ModuleContext& ctx, const Options& o) : ctx_(ctx), o_(o) {}

  // The (temporary) folder of a stage, staged on first use.
  std::string Folder(const std::string& stage) {
    auto it = folders_.find(stage);
    if (it == folders_.end())
      it = folders_.emplace(stage, ctx_.outputs.StageDirectory((fs::path(o_.out) / stage).string(),
                                                               stage + " folder")).first;
    return it->second;
  }
  std::string In(const std::string& stage, const std::string& file) { return (fs::path(Folder(stage)) / file).string(); }

  std::map<std::string, std::string> Run(const std::string& stage, const StageModule& m,
                                         const std::vector<std::string>& args) {
    ctx_.progress.StartStage(stage);
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = cli::ProcessCpuSeconds();
    std::map<std::string, std::string> results;
    try {
      results = cli::RunNestedModule(static_cast<cli::ProgressParent&>(ctx_.progress), m.name, m.xml, m.body, args, &shelf_);
    } catch (const Error& e) {
      // Stage folders are hidden temporaries until the end: the message names the final folders.
      throw Error(ctx_.outputs.UserNames(e.what()));
    }
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpuSeconds = cli::ProcessCpuSeconds() - cpuStart;
    ctx_.progress.EndStage();
    stages_.push_back({{"name", stage}, {"module", m.name}, {"seconds", seconds}, {"cpuSeconds", cpuSeconds},
                       {"results", ResultsJson(results)}});
    return results;
  }

  // Two jobs as one stage of the host's progress (issue 22): the two scans' (their notes say
  // which scan) or the two views modules' (scanJobs false), side by side on two threads
  // (Core/RunConcurrently.h; the outputs are the same as one after the other, tested), or, with
  // --sequential, the first job and then the second. Each step keeps its own record (its wall
  // time and its thread's CPU time); the block's wall and process CPU time are recorded in
  // `blocks`. Stage folders must exist before (Folder() is not for threads).
  void RunBoth(const std::string& stage, const std::array<std::vector<Step>, 2>& jobs, bool scanJobs = true) {
    ctx_.progress.StartStage(stage);
    const auto start = std::chrono::steady_clock::now();
    const double cpuStart = cli::ProcessCpuSeconds();
    const auto records = RunJobs(jobs, scanJobs);
    for (const auto& job : records)
      for (const cli::StepRecord& r : job)
        ctx_.progress.Note("ColonSupineProne: " + r.name + " done in " + cli::FormatFixed(r.seconds, 2) + " s" +
                           (o_.sideBySide ? " (side by side with the other job)" : ""));
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const double cpuSeconds = cli::ProcessCpuSeconds() - cpuStart;
    ctx_.progress.EndStage();
    RecordBlock(stage, records, seconds, cpuSeconds);
  }

  // The two jobs, side by side or one after the other, into the current stage's progress; their
  // notes printed (also when one fails); their steps' records.
  std::array<std::vector<cli::StepRecord>, 2> RunJobs(const std::array<std::vector<Step>, 2>& jobs, bool scanJobs) {
    std::array<std::vector<cli::StepRecord>, 2> records;
    std::array<std::vector<std::string>, 2> notes;
    std::array<std::vector<std::pair<std::string, std::string>>, 2> failures;
    auto job = [&](int k) {
      return [&, k](ProgressSink& sink) {
        std::vector<std::pair<std::string, double>> plan;
        for (const Step& s : jobs[k]) plan.emplace_back(s.name, s.weight);
        cli::StageChain chain(sink, plan, [this] { return ctx_.progress.AbortRequested(); }, &shelf_);
        try {
          for (const Step& s : jobs[k]) {
            try {
              chain.Run(s.name, s.module.name, s.module.xml, s.module.body, s.args);
            } catch (const Error& e) {
              if (!s.optional) throw;
              failures[k].emplace_back(s.name, e.what());
            }
          }
        } catch (...) {
          notes[k] = chain.TakeNotes();
          throw;
        }
        records[k] = chain.Records();
        notes[k] = chain.TakeNotes();
      };
    };
    try {
      if (o_.sideBySide) {
        io::PrepareToolkitsForThreads();
        RunConcurrently(job(0), job(1), ctx_.progress);
      } else {
        SubProgress first(ctx_.progress, 0.0, 0.5), second(ctx_.progress, 0.5, 1.0);
        job(0)(first);
        job(1)(second);
      }
    } catch (const Error& e) {
      PrintNotes(notes, scanJobs);
      throw Error(ctx_.outputs.UserNames(e.what()));
    } catch (...) {  // Cancel, out of memory: what the finished steps said still counts
      PrintNotes(notes, scanJobs);
      throw;
    }
    PrintNotes(notes, scanJobs);
    for (const auto& job : failures)
      for (const auto& [step, message] : job) failures_[step] = ctx_.outputs.UserNames(message);
    return records;
  }

  // The block's stage records (each step's own) and its own record (wall and process CPU).
  void RecordBlock(const std::string& stage, const std::array<std::vector<cli::StepRecord>, 2>& records,
                   double seconds, double cpuSeconds) {
    json names = json::array();
    for (const auto& job : records)
      for (const cli::StepRecord& r : job) {
        stages_.push_back({{"name", r.name}, {"module", r.module}, {"seconds", r.seconds},
                           {"threadCpuSeconds", r.threadCpuSeconds}, {"block", stage}, {"results", ResultsJson(r.results)}});
        names.push_back(r.name);
      }
    blocks_.push_back({{"name", stage}, {"stages", names}, {"sideBySide", o_.sideBySide}, {"seconds", seconds},
                       {"cpuSeconds", cpuSeconds}});
  }

  // The jobs' notes, the first job's first; for the scans' jobs each line says its scan (the
  // stages' own notes do not).
  void PrintNotes(const std::array<std::vector<std::string>, 2>& notes, bool scanJobs) {
    for (int k = 0; k < 2; ++k)
      for (const auto& line : notes[k]) ctx_.progress.Note(scanJobs ? std::string(kScans[k]) + ": " + line : line);
  }

  // The error of an optional step that failed (RunBoth), or nothing.
  std::optional<std::string> Failure(const std::string& step) const {
    const auto it = failures_.find(step);
    return it == failures_.end() ? std::nullopt : std::optional<std::string>(it->second);
  }

  // Volumes one stage hands to the next in memory (the files are written all the same).
  VolumeShelf& Shelf() { return shelf_; }

  const std::map<std::string, std::string>& Folders() const { return folders_; }
  const json& Stages() const { return stages_; }
  const json& Blocks() const { return blocks_; }
  double TotalSeconds() const { return WallSeconds(stages_, blocks_); }

 private:
  cli::ModuleContext& ctx_;
  const Options& o_;
  std::map<std::string, std::string> folders_;
  json stages_ = json::array();
  json blocks_ = json::array();
  std::map<std::string, std::string> failures_;  // optional steps that failed: their errors
  VolumeShelf shelf_;
};

std::string DescriptionField(const std::string& description, const std::string& key) {
  std::smatch m;
  return std::regex_search(description, m, std::regex("(^| )" + key + "=([^ ]+)")) ? m[2].str() : std::string();
}

// The findings table of summary.json: supine and mapped prone positions, the transfer's
// uncertainty and, with a phantom truth carrying the same labels, the true error.
json FindingsTable(const MarkupList& supine, const MarkupList& prone, const MarkupList* truth) {
  json rows = json::array();
  for (std::size_t i = 0; i < supine.points.size() && i < prone.points.size(); ++i) {
    const auto& s = supine.points[i];
    const auto& p = prone.points[i];
    json row{{"label", s.label},
             {"supine", {s.position.x(), s.position.y(), s.position.z()}},
             {"prone", {p.position.x(), p.position.y(), p.position.z()}},
             {"segment", DescriptionField(p.description, "segment")}};
    const std::string u = DescriptionField(p.description, "uncertaintyMm");
    if (!u.empty()) row["uncertaintyMm"] = std::stod(u);
    const std::string r = DescriptionField(p.description, "reliable");
    if (!r.empty()) row["reliable"] = r == "true";
    // Collapsed stretches (issue 21): a finding on wall not seen in one scan says so.
    if (DescriptionField(p.description, "visible") == "false") {
      row["visible"] = false;
      row["notSeenIn"] = DescriptionField(p.description, "notSeenIn") == "source" ? "supine" : "prone";
      const std::string d = DescriptionField(p.description, "alongColonToOpenMm");
      if (!d.empty()) row["alongColonToOpenMm"] = std::stod(d);
    }
    if (truth)
      for (const auto& t : truth->points)
        if (t.label == s.label) row["trueErrorMm"] = (t.position - p.position).norm();
    rows.push_back(row);
  }
  return rows;
}

// Scene outputs (Slicer's model nodes), when asked for: the registration folder's two surfaces.
void WriteModelNodes(cli::ModuleContext& ctx, const std::string& registrationFolder) {
  for (const auto& [param, file, what] :
       {std::tuple<const char*, const char*, const char*>{"registrationModel", "registration.vtp", "registration model"},
        {"proneModel", "registration_prone.vtp", "prone surface model"}})
    if (const std::string node = ctx.args.GetString(param); !node.empty())
      io::CopyNodeFile(io::NodeFileKind::Model, (fs::path(registrationFolder) / file).string(), ctx.outputs.Stage(node, what),
                       what);
}

// Scene outputs for the findings, when asked for: the transferred findings (the markups file
// ColonTransferPoints wrote: label, uncertaintyMm and reliable in each description) and the
// findings table of summary.json as a table node (.tsv or .csv, as the file name says).
void WriteFindingsNodes(cli::ModuleContext& ctx, const std::string& mapped, const json& rows) {
  if (const std::string node = ctx.args.GetString("findingsProne"); !node.empty())
    io::CopyNodeFile(io::NodeFileKind::Markups, mapped, ctx.outputs.Stage(node, "findings in the prone scan"),
                     "findings in the prone scan");
  const std::string tablePath = ctx.args.GetString("findingsTable");
  if (tablePath.empty()) return;
  io::TextTable t;
  t.columns = {"label", "supine_L", "supine_P", "supine_S", "prone_L", "prone_P", "prone_S", "segment",
               "uncertainty_mm", "reliable", "visible", "true_error_mm"};
  const auto number = [](const json& v) { return v.is_number() ? cli::FormatFixed(v.get<double>(), 2) : std::string(); };
  for (const json& r : rows) {
    std::vector<std::string> row{r.value("label", "")};
    for (const char* scan : {"supine", "prone"})
      for (int k = 0; k < 3; ++k) row.push_back(number(r[scan][k]));
    row.push_back(r.value("segment", ""));
    row.push_back(number(r.value("uncertaintyMm", json())));
    row.push_back(r.contains("reliable") ? (r["reliable"].get<bool>() ? "true" : "false") : "");
    row.push_back(r.value("visible", true) ? "true" : "false");
    row.push_back(number(r.value("trueErrorMm", json())));
    t.rows.push_back(row);
  }
  io::WriteTable(t, ctx.outputs.Stage(tablePath, "findings table"), "findings table");
}

std::vector<std::pair<std::string, double>> Plan(const Options& o) {
  // The two scans' jobs are one stage each (Pipeline::RunBoth), weighing both scans' steps.
  std::vector<std::pair<std::string, double>> plan;
  if (o.labelMaps) plan.emplace_back(kLabelMapsStage, 2 * kSurfaceWeight);
  else plan.emplace_back(kScansStage, 2 * (kCleansingWeight + kSegmentationWeight + kSurfaceWeight));
  plan.emplace_back("landmarks", 4.0);
  plan.emplace_back(kFlatteningStage, 2 * kFlatteningWeight);
  plan.emplace_back("registration", 2.0);
  if (!o.findings.empty()) plan.emplace_back("transfer findings", 0.2);
  const double views = (o.views ? kFlatViewsWeight : 0.0) + (EndoluminalViews(o) ? kEndoluminalViewsWeight : 0.0);
  if (views > 0) plan.emplace_back(kViewsStage, views);
  if (!o.truth.empty()) plan.emplace_back("evaluation", 0.3);
  plan.emplace_back("report", 0.2);
  return plan;
}

void CheckInputs(const Options& o, bool scansMustExist = true) {
  for (int k = 0; k < 2 && scansMustExist; ++k) {
    if (o.scan[k].empty()) throw Error(std::string(kScans[k]) + " scan: no file given (--" + kScans[k] + ")");
    // Format, header and geometry, without the voxels: a bad prone CT must stop the run before
    // the supine half is done, not after it (issue 24). A host's "slicer:" node passes.
    io::CheckImageFile(o.scan[k], std::string(kScans[k]) + " scan");
  }
  // Everything else read late in the pipeline is read now too, for the same reason.
  if (!o.findings.empty()) {
    if (!fs::is_regular_file(o.findings)) throw InputError("findings", o.findings, "does not exist");
    if (io::ReadMarkups(o.findings, "findings").points.empty()) throw InputError("findings", o.findings, "holds no points");
  }
  if (!o.truth.empty()) {
    for (const char* f : {"supine_eval.mrk.json", "prone_eval.mrk.json"}) {
      const fs::path t = fs::path(o.truth) / f;
      if (!fs::is_regular_file(t))
        throw InputError("ground truth folder", o.truth, std::string("has no ") + f + " (a ColonPhantom output folder)");
      io::ReadMarkups(t.string(), std::string("ground truth ") + f);
    }
  }
}

// summary.json and report.html from the stage records and the (possibly temporary) stage folders;
// the return parameters and the closing note. Shared by the whole run and --reportOnly.
void WriteSummaryAndReport(cli::ModuleContext& ctx, const Options& o, const json& stages, const json& blocks,
                           double totalSeconds,
                           const std::map<std::string, std::string>& folders, const json& notes,
                           const json& findingsTable) {
  const auto in_ = [&](const std::string& stage, const std::string& file) {
    const auto it = folders.find(stage);
    return it == folders.end() ? std::string() : (fs::path(it->second) / file).string();
  };
  report::PipelineReportInput in;
  for (int k = 0; k < 2; ++k) {
    in.stages.landmarks[k] = report::ReadJsonOrNull(in_("landmarks", std::string(kScans[k]) + "/landmarks.json"));
    in.stages.flattening[k] = report::ReadJsonOrNull(in_("flattening", std::string(kScans[k]) + "/flattening.json"));
  }
  in.stages.registration = report::ReadJsonOrNull(in_("registration", "registration.json"));
  in.flags = report::AssessQuality(in.stages);
  json flags = json::array();
  int warnings = 0;
  for (const auto& f : in.flags) {
    flags.push_back({{"name", f.name}, {"ok", f.ok}, {"detail", f.detail}});
    warnings += f.ok ? 0 : 1;
  }
  in.summary = {{"inputs", {{"supine", o.scan[0]}, {"prone", o.scan[1]}, {"labelMaps", o.labelMaps},
                            {"findings", o.findings}, {"groundTruth", o.truth}}},
                {"method", o.method},
                {"stages", stages},
                {"stageBlocks", blocks},
                {"totalSeconds", totalSeconds},
                {"quality", flags},
                {"warnings", warnings},
                {"notes", notes},
                {"findings", findingsTable}};
  // Only for a collapsed colon: a colon in one piece keeps its summary.json.
  if (const json pieces = report::PiecesSummary(stages, in.stages.registration); !pieces.is_null())
    in.summary["pieces"] = pieces;
  in.folders = folders;
  io::WriteText(in.summary.dump(2) + "\n", ctx.outputs.Stage((fs::path(o.out) / "summary.json").string(), "summary.json"),
                "summary.json");
  io::WriteText(report::PipelineReportHtml(in), ctx.outputs.Stage((fs::path(o.out) / "report.html").string(), "report.html"),
                "report.html");
  ctx.progress.EndStage();

  ctx.SetReturn("totalSeconds", cli::FormatFixed(totalSeconds, 2));
  ctx.SetReturn("warnings", std::to_string(warnings));
  ctx.progress.Note("ColonSupineProne: " + cli::FormatFixed(totalSeconds, 1) + " s, " + std::to_string(warnings) +
                    " quality warning(s); report: " + (fs::path(o.out) / "report.html").string());
}

// The stage reports --reportOnly reads, checked at the door: each must exist, and be what its
// reader (IO/StageReports) accepts, so a damaged one is refused naming it instead of leaving a
// section of the report out.
void CheckStageReports(const Options& o) {
  const fs::path out(o.out);
  for (const char* file : {"landmarks/supine/landmarks.json", "landmarks/prone/landmarks.json",
                           "flattening/supine/flattening.json", "flattening/prone/flattening.json",
                           "registration/registration.json"})
    if (!fs::is_regular_file(out / file))
      throw InputError("output folder", o.out, std::string("has no ") + file + " (run the stages before --reportOnly)");
  for (const char* scan : kScans) {
    io::ReadLandmarksReport((out / "landmarks" / scan / "landmarks.json").string(), std::string(scan) + " landmarks report");
    io::ReadFlatteningReport((out / "flattening" / scan / "flattening.json").string(), std::string(scan) + " flattening report");
  }
  io::ReadRegistrationReport((out / "registration" / "registration.json").string(), "registration report");
}

// --reportOnly: summary.json and report.html from the stage folders already under the output folder
// (made by the stage modules run one at a time, e.g. by the cohort workflow, scripts/cohort/).
// The stage times and results come from --stageRecords; nothing else is run or changed.
void BuildReportOnly(cli::ModuleContext& ctx, const Options& o, const std::string& recordsPath) {
  const fs::path out(o.out);
  if (!fs::is_directory(out)) throw InputError("output folder", o.out, "does not exist (--reportOnly reads the stage folders in it)");
  std::map<std::string, std::string> folders;
  for (const char* stage : {"cleansing", "segmentation", "surface", "landmarks", "flattening", "registration",
                            "flatviews", "transfer", "views", "evaluation"})
    if (fs::is_directory(out / stage)) folders[stage] = (out / stage).string();
  CheckStageReports(o);
  json stages = json::array(), notes = json::array(), blocks = json::array();
  if (!recordsPath.empty()) {
    const json records = report::ReadJsonOrNull(recordsPath);
    if (!records.is_object() || !records.value("stages", json()).is_array())
      throw InputError("stage records", recordsPath, "is not a JSON object with a \"stages\" array");
    stages = records["stages"];
    if (records.value("notes", json()).is_array()) notes = records["notes"];
    if (records.value("stageBlocks", json()).is_array()) blocks = records["stageBlocks"];
  }
  const double totalSeconds = WallSeconds(stages, blocks);
  json findingsTable = json::array();
  if (!o.findings.empty()) {
    const fs::path mapped = out / "transfer" / "findings_prone.mrk.json";
    if (!fs::is_regular_file(mapped))
      throw InputError("output folder", o.out, "has no transfer/findings_prone.mrk.json for the findings (run ColonTransferPoints)");
    const fs::path t = fs::path(o.truth) / "prone_polyps.mrk.json";
    const MarkupList truth = o.truth.empty() || !fs::exists(t) ? MarkupList{} : io::ReadMarkups(t.string(), "true prone polyps");
    findingsTable = FindingsTable(io::ReadMarkups(o.findings, "findings"), io::ReadMarkups(mapped.string(), "mapped findings"),
                                  truth.points.empty() ? nullptr : &truth);
    WriteFindingsNodes(ctx, mapped.string(), findingsTable);
    bool said = false;
    for (const auto& n : notes) said = said || (n.is_string() && n.get<std::string>().rfind("No endoluminal views", 0) == 0);
    if (o.labelMaps && !said)
      notes.push_back("No endoluminal views: the inputs are label maps, there is no CT to render.");
    else if (o.views && !folders.count("views") && !said)
      notes.push_back("No endoluminal views: " + (out / "views").string() + " does not exist.");
  }
  if (!o.truth.empty()) {
    const json errors = report::ReadJsonOrNull((out / "evaluation" / "errors.json").string());
    const json mean = errors.is_object() ? errors.value("overall", json::object()).value("error3D", json::object()).value("mean", json())
                                         : json();
    if (!mean.is_number())
      throw InputError("output folder", o.out, "has no evaluation/errors.json for the ground truth (run ColonEvaluateRegistration)");
    ctx.SetReturn("meanError", cli::FormatNumber(mean.get<double>()));
  }
  WriteModelNodes(ctx, (out / "registration").string());
  ctx.progress.Plan({{"report", 0.2}});
  ctx.progress.StartStage("report");
  WriteSummaryAndReport(ctx, o, stages, blocks, totalSeconds, folders, notes, findingsTable);
}

// The report reads many fields of the stage files beyond those IO/StageReports checks; our modules
// write them, but in --reportOnly a user's folder may hold one edited or damaged by hand, with a
// field of another type: that is the folder's problem, said in one line, not an internal error.
void RunReportOnly(cli::ModuleContext& ctx, const Options& o, const std::string& recordsPath) {
  try {
    BuildReportOnly(ctx, o, recordsPath);
  } catch (const json::exception& e) {
    throw InputError("output folder", o.out, std::string("holds a stage file the report cannot read (") + e.what() + ")");
  }
}

void Run(cli::ModuleContext& ctx) {
  Options o;
  o.scan[0] = ctx.args.GetString("supine");
  o.scan[1] = ctx.args.GetString("prone");
  o.out = ctx.args.GetString("outputDirectory");
  o.findings = ctx.args.GetString("findings");
  o.truth = ctx.args.GetString("groundTruth");
  o.method = ctx.args.GetString("method");
  o.labelMaps = ctx.args.GetBool("labelMaps");
  o.views = !ctx.args.GetBool("skipViews");
  o.sideBySide = !ctx.args.GetBool("sequential");
  o.targetFaces = std::to_string(ctx.args.GetInt("targetFaces"));
  o.labelValue = std::to_string(ctx.args.GetInt("labelValue"));
  if (o.out.empty()) throw Error("output folder: no folder given (--outputDirectory)");
  for (const char* node : {"findingsProne", "findingsTable"})
    if (o.findings.empty() && !ctx.args.GetString(node).empty())
      throw Error(std::string("parameter --") + node + ": needs findings (--findings) to transfer");
  if (ctx.args.GetBool("reportOnly")) {
    CheckInputs(o, /*scansMustExist=*/false);  // the scans are only named in summary.json, not read
    return RunReportOnly(ctx, o, ctx.args.GetString("stageRecords"));
  }
  CheckInputs(o);
  ctx.outputs.PrepareDirectory(o.out, "output folder");
  ctx.progress.Plan(Plan(o));

  Pipeline p(ctx, o);
  json notes = json::array();
  std::string volume[2];  // what the endoluminal views render
  std::array<std::vector<Step>, 2> scanJobs, flatJobs;
  // The jobs' folders, made here: the threads only use their names.
  if (!o.labelMaps) p.Folder("cleansing"), p.Folder("segmentation");
  for (const char* stage : {"surface", "landmarks", "flattening"}) p.Folder(stage);
  for (int k = 0; k < 2; ++k) {
    const std::string scan = kScans[k];
    const std::string surface = p.In("surface", scan + "_surface.vtp");
    if (!o.labelMaps) {
      const std::string cleansed = p.In("cleansing", scan + "_cleansed.nrrd");
      const std::string lumen = p.In("segmentation", scan + "_lumen.nrrd");
      // A colon in pieces (collapsed stretches) is bridged by virtual lumen, and its wall marked
      // (issue 21); a colon in one piece gives the same files as without.
      const std::string virtualLumen = p.In("segmentation", scan + "_virtual.nrrd");
      // Handed on in memory: the cleansed CT to segmentation, surface and the endoluminal views,
      // the labels to surface.
      p.Shelf().Expect(cleansed, EndoluminalViews(o) ? 3 : 2);
      p.Shelf().Expect(lumen, 1);
      p.Shelf().Expect(virtualLumen, 1);
      scanJobs[k].push_back({"cleansing " + scan, COLONMAP_STAGE(ColonCleansing),
                             {o.scan[k], cleansed, "--taggedLabel", p.In("cleansing", scan + "_tagged.nrrd")}, kCleansingWeight});
      scanJobs[k].push_back({"segmentation " + scan, COLONMAP_STAGE(ColonSegmentation),
                             {cleansed, lumen, "--bridgePieces", "--bridgeLabel", virtualLumen}, kSegmentationWeight});
      scanJobs[k].push_back({"surface " + scan, COLONMAP_STAGE(ColonSurface),
                             {lumen, surface, "--referenceCT", cleansed, "--targetFaces", o.targetFaces, "--virtualLabel",
                              virtualLumen},
                             kSurfaceWeight});
      volume[k] = cleansed;
    } else {
      scanJobs[k].push_back({"surface " + scan, COLONMAP_STAGE(ColonSurface),
                             {o.scan[k], surface, "--labelValue", o.labelValue, "--targetFaces", o.targetFaces}, kSurfaceWeight});
    }
    flatJobs[k].push_back({"flattening " + scan, COLONMAP_STAGE(ColonFlattening),
                           {p.In("landmarks", scan), p.In("flattening", scan)}, kFlatteningWeight});
  }
  p.RunBoth(o.labelMaps ? kLabelMapsStage : kScansStage, scanJobs);
  // Both scans at once: their flexures are chosen together (the same anatomy in both).
  p.Run("landmarks", COLONMAP_STAGE(ColonLandmarks),
        {p.In("surface", "supine_surface.vtp"), p.In("landmarks", "supine"), "--pairedSurface",
         p.In("surface", "prone_surface.vtp"), "--pairedOutputDirectory", p.In("landmarks", "prone"), "--scanNames",
         "supine,prone"});
  p.RunBoth(kFlatteningStage, flatJobs);
  const std::string reg = p.In("registration", "registration.vtp");
  p.Run("registration", COLONMAP_STAGE(ColonRegistration),
        {p.In("flattening", "supine"), p.In("flattening", "prone"), p.Folder("registration"), "--method", o.method});
  for (const char* file : {"registration.vtp", "registration_prone.vtp"})
    fs::copy_file(p.In("registration", file), ctx.outputs.Stage((fs::path(o.out) / file).string(), file));
  WriteModelNodes(ctx, p.Folder("registration"));

  json findingsTable = json::array();
  if (!o.findings.empty()) {
    const std::string mapped = p.In("transfer", "findings_prone.mrk.json");
    p.Run("transfer findings", COLONMAP_STAGE(ColonTransferPoints),
          {"--registration", reg, "--input", o.findings, "--output", mapped});
    const MarkupList truth = o.truth.empty() || !fs::exists(fs::path(o.truth) / "prone_polyps.mrk.json")
                                 ? MarkupList{}
                                 : io::ReadMarkups((fs::path(o.truth) / "prone_polyps.mrk.json").string(), "true prone polyps");
    findingsTable = FindingsTable(io::ReadMarkups(o.findings, "findings"), io::ReadMarkups(mapped, "mapped findings"),
                                  truth.points.empty() ? nullptr : &truth);
    WriteFindingsNodes(ctx, mapped, findingsTable);
    if (o.labelMaps) notes.push_back("No endoluminal views: the inputs are label maps, there is no CT to render.");
  }
  // The flat views and the endoluminal views side by side (each renders in its own VTK window on
  // its own X connection). Rendering needs an X display: without one the flat views leave out
  // their 3D pictures and the endoluminal views fail, and the rest of the run still stands.
  std::array<std::vector<Step>, 2> viewJobs;
  if (o.views)
    viewJobs[0].push_back({"flat views", COLONMAP_STAGE(ColonFlatViews),
                           {p.In("flattening", "supine"), p.In("flattening", "prone"), p.Folder("registration"),
                            p.Folder("flatviews")},
                           kFlatViewsWeight});
  if (EndoluminalViews(o))
    viewJobs[1].push_back({"endoluminal views", COLONMAP_STAGE(ColonEndoluminalViews),
                           {"--supineVolume", volume[0], "--proneVolume", volume[1], "--registration", reg, "--findings",
                            o.findings, p.Folder("views")},
                           kEndoluminalViewsWeight, /*optional=*/true});
  if (!viewJobs[0].empty() || !viewJobs[1].empty()) {
    p.RunBoth(kViewsStage, viewJobs, /*scanJobs=*/false);
    // Read or not (no display), the cleansed CTs are not needed any more.
    for (const std::string& v : volume) p.Shelf().Drop(v);
    if (const auto failure = p.Failure("endoluminal views")) {
      notes.push_back("No endoluminal views: " + *failure);
      ctx.progress.Note("ColonSupineProne: WARNING: no endoluminal views: " + *failure);
    }
  }
  if (!o.truth.empty()) {
    const fs::path t(o.truth);
    std::vector<std::string> args{"--registration", reg, "--truthSupine", (t / "supine_eval.mrk.json").string(),
                                  "--truthProne", (t / "prone_eval.mrk.json").string()};
    if (fs::exists(t / "supine_polyps.mrk.json") && fs::exists(t / "prone_polyps.mrk.json"))
      args.insert(args.end(), {"--polypsSupine", (t / "supine_polyps.mrk.json").string(), "--polypsProne",
                               (t / "prone_polyps.mrk.json").string()});
    args.insert(args.end(), {"--output", p.In("evaluation", "errors.json"), "--outputTable",
                             p.In("evaluation", "errors.tsv")});
    const auto r = p.Run("evaluation", COLONMAP_STAGE(ColonEvaluateRegistration), args);
    ctx.SetReturn("meanError", r.count("meanError") ? r.at("meanError") : "0");
  }

  ctx.progress.StartStage("report");
  std::map<std::string, std::string> folders;
  for (const auto& [stage, folder] : p.Folders()) folders[stage] = folder;
  WriteSummaryAndReport(ctx, o, p.Stages(), p.Blocks(), p.TotalSeconds(), folders, notes, findingsTable);
}

}  // namespace

COLONMAP_MODULE_BODY(ColonSupineProne, Run)
