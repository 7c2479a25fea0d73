#pragma once
// report.html of ColonSupineProne (issue 9): one page with the quality flags, the registration
// error when a ground truth was given, the flattened pair before and after registration, the
// matched features, the distortion maps, the findings with their linked endoluminal views, the
// per-segment figures and the stage times. Images are read from the stage folders and embedded.
#include "Report/QualityFlags.h"

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

namespace colonmap::report {

struct PipelineReportInput {
  nlohmann::json summary;                      // what ColonSupineProne writes as summary.json
  StageSummaries stages;                       // the stages' own JSON summaries
  std::vector<QualityFlag> flags;
  // Where each stage folder is now (during the run they have temporary names): "flatviews",
  // "views", "transfer", "evaluation", ... -> path. Absent: that stage did not run.
  std::map<std::string, std::string> folders;
};

std::string PipelineReportHtml(const PipelineReportInput& in);

// The pieces each scan's colon came in (issue 21), from ColonSupineProne's stage records (the
// segmentation stages' return parameters) and registration.json: per scan pieces,
// pieceLengthsMm (from the caecum), gapsBridgedMm, virtualLumenMl and wallNotSeen (segment ->
// fraction of its wall that is virtual). Null when both colons came in one piece.
nlohmann::json PiecesSummary(const nlohmann::json& stages, const nlohmann::json& registration);

// A stage's JSON summary, or null when the file is missing or not JSON (that stage did not run).
nlohmann::json ReadJsonOrNull(const std::string& path);

}  // namespace colonmap::report
