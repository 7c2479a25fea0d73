#pragma once
// The quality flags of a pipeline run (issue 9): what a reader checks before trusting the
// registration, computed from the stages' own JSON summaries (landmarks.json, flattening.json,
// registration.json; DESIGN §2.0). Missing summaries (a stage that did not run) give no flag.
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace colonmap::report {

struct QualityFlag {
  std::string name;
  bool ok = true;
  std::string detail;  // the figures behind the verdict, and what to do when it is not OK
};

struct QualityThresholds {
  double minTaeniaConfidence = 0.15;  // below: the cut taenia is a guess
  int minMatchedFeatures = 3;         // per segment; fewer: the segment keeps the conformal map
  double maxMeanBeltrami = 0.05;      // per flattened segment
  double maxLengthRatio = 1.35;       // supine/prone segment length, either way round
  double maxAlignmentCost = 0.25;     // mean direction difference of the aligned centrelines (0.08-0.09 measured on GCA 00020 pairs)
};

struct StageSummaries {
  nlohmann::json landmarks[2];   // supine, prone; null when absent
  nlohmann::json flattening[2];
  nlohmann::json registration;
};

std::vector<QualityFlag> AssessQuality(const StageSummaries& s, const QualityThresholds& t = {});

}  // namespace colonmap::report
