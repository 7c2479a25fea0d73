#include "Report/QualityFlags.h"

#include <algorithm>
#include <cstdio>

namespace colonmap::report {
namespace {

using nlohmann::json;

const char* const kScan[2] = {"supine", "prone"};
const char* const kSegments[5] = {"A", "T", "D", "S", "R"};
const char* const kFlexures[4] = {"RSJ", "DSJ", "SF", "HF"};  // order from the anal end

std::string Fixed(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

double Number(const json& j, const char* key, double fallback) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? j[key].get<double>() : fallback;
}

void FlexureFlags(const StageSummaries& s, std::vector<QualityFlag>& flags) {
  for (int k = 0; k < 2; ++k) {
    const json& l = s.landmarks[k];
    if (l.is_null()) continue;
    QualityFlag f{std::string("Four flexures found (") + kScan[k] + ")", true, ""};
    double last = -1.0;
    for (const char* name : kFlexures) {
      const json flex = l.value("flexures", json::object()).value(name, json());
      const double arc = Number(flex, "arcLengthMm", -1.0);
      if (arc < 0.0) {
        f.ok = false;
        f.detail += std::string(name) + " missing; ";
        continue;
      }
      if (arc <= last) f.ok = false;
      last = arc;
      f.detail += std::string(name) + " " + Fixed(arc, 0) + " mm, ";
    }
    f.detail += "from the anal end" + std::string(f.ok ? "" : " (not in anatomical order: check the landmarks)");
    flags.push_back(f);
  }
}

void TaeniaFlags(const StageSummaries& s, const QualityThresholds& t, std::vector<QualityFlag>& flags) {
  if (s.landmarks[0].is_null() || s.landmarks[1].is_null()) return;
  QualityFlag confidence{"Taenia confidence", true, ""};
  QualityFlag same{"Same cut taenia in both scans", true, ""};
  for (const char* seg : kSegments) {
    std::string cut[2];
    for (int k = 0; k < 2; ++k) {
      const json segment = s.landmarks[k].value("segments", json::object()).value(seg, json());
      const double c = Number(segment, "taeniaConfidence", 0.0);
      cut[k] = segment.is_object() ? segment.value("cutTaenia", std::string("?")) : "?";
      if (c < t.minTaeniaConfidence) {
        confidence.ok = false;
        confidence.detail += std::string(seg) + " " + kScan[k] + " " + Fixed(c, 2) + " low; ";
      }
    }
    same.detail += std::string(seg) + " " + cut[0] + "/" + cut[1] + " ";
    if (cut[0] != cut[1]) same.ok = false;
  }
  if (confidence.ok) confidence.detail = "every segment at least " + Fixed(t.minTaeniaConfidence, 2);
  else confidence.detail += "the cut may run off the band there; the registration corrects a cyclic shift";
  same.detail += same.ok ? "(supine/prone)" : "(supine/prone): the registration aligns them by a cyclic shift";
  flags.push_back(confidence);
  flags.push_back(same);
}

void LengthFlag(const StageSummaries& s, const QualityThresholds& t, std::vector<QualityFlag>& flags) {
  if (s.landmarks[0].is_null() || s.landmarks[1].is_null()) return;
  QualityFlag f{"Segment lengths agree", true, ""};
  for (const char* seg : kSegments) {
    const double a = Number(s.landmarks[0].value("segments", json::object()).value(seg, json()), "lengthMm", 0.0);
    const double b = Number(s.landmarks[1].value("segments", json::object()).value(seg, json()), "lengthMm", 0.0);
    const double ratio = a > 0.0 && b > 0.0 ? std::max(a / b, b / a) : 0.0;
    f.detail += std::string(seg) + " " + Fixed(a, 0) + "/" + Fixed(b, 0) + " mm, ";
    if (ratio == 0.0 || ratio > t.maxLengthRatio) f.ok = false;
  }
  f.detail += f.ok ? "supine/prone" : "supine/prone: a flexure may be misplaced in one scan";
  flags.push_back(f);
}

// The flexures chosen for both scans together (ColonLandmarks with --pairedSurface): not
// trusted when no ordered joint choice existed (the segments then come from the centreline
// alignment alone) or the alignment itself was poor.
void JointFlexureFlag(const StageSummaries& s, const QualityThresholds& t, std::vector<QualityFlag>& flags) {
  if (s.landmarks[0].is_null()) return;
  const json joint = s.landmarks[0].value("jointChoice", json());
  if (!joint.is_object() || joint.value("pairedWith", std::string()).empty()) return;  // one scan alone
  QualityFlag f{"Flexures chosen jointly", true, ""};
  const bool consistent = joint.value("consistent", false), fallback = joint.value("fallback", false);
  const double cost = Number(joint, "alignmentCost", 1.0);
  for (const char* name : {"HF", "SF", "DSJ", "RSJ"}) {
    const json fl = joint.value("flexures", json::object()).value(name, json());
    const std::string how = fl.is_object() ? fl.value("choice", std::string("?")) : std::string("missing");
    f.detail += std::string(name) + " " + how + ", ";
  }
  f.detail += "centreline alignment " + Fixed(cost, 2);
  if (!consistent || cost > t.maxAlignmentCost) {
    f.ok = false;
    f.detail += fallback ? "; no ordered choice: segments from the centreline alignment, pairing not trusted"
                         : (!consistent ? "; no ordered choice: each scan's own flexures" : "; the centrelines align poorly");
  }
  flags.push_back(f);
}

void FlatteningFlags(const StageSummaries& s, const QualityThresholds& t, std::vector<QualityFlag>& flags) {
  for (int k = 0; k < 2; ++k) {
    const json& fl = s.flattening[k];
    if (fl.is_null()) continue;
    QualityFlag f{std::string("Flattening conformal, no flips (") + kScan[k] + ")", true, ""};
    const int flips = static_cast<int>(Number(fl, "flippedTriangles", -1.0));
    if (flips != 0) f.ok = false;
    f.detail = std::to_string(flips) + " flipped triangles; mean |mu|";
    for (const char* seg : kSegments) {
      const json segment = fl.value("segments", json::object()).value(seg, json());
      if (!segment.is_object()) {
        f.ok = false;
        f.detail += std::string(" ") + seg + " missing";
        continue;
      }
      const double mu = Number(segment.value("beltramiAbs", json::object()), "mean", 1.0);
      if (mu > t.maxMeanBeltrami) f.ok = false;
      f.detail += std::string(" ") + seg + " " + Fixed(mu, 3);
    }
    flags.push_back(f);
  }
}

void RegistrationFlags(const StageSummaries& s, const QualityThresholds& t, std::vector<QualityFlag>& flags) {
  const json& r = s.registration;
  if (r.is_null()) return;
  // Collapsed stretches bridged by virtual lumen (issue 21), when a scan had one.
  {
    std::string detail;
    for (const char* seg : kSegments) {
      const json segment = r.value("segments", json::object()).value(seg, json());
      if (!segment.is_object()) continue;
      for (const auto& [key, scan] : {std::pair{"supineVirtualFraction", "supine"}, std::pair{"proneVirtualFraction", "prone"}})
        if (const double f = Number(segment, key, 0.0); f > 0.0)
          detail += std::string(seg) + " " + scan + " " + Fixed(100.0 * f, 0) + "%, ";
    }
    if (!detail.empty())
      flags.push_back({"Colon open in both scans", false,
                       "wall not seen (collapsed, bridged by virtual lumen): " + detail +
                           "findings there are marked visible=false and placed at the nearest open wall"});
  }
  // The registration's own trust of each segment (RegistrationReliability.h), when it says.
  if (r.contains("untrustedSegments") && r["untrustedSegments"].is_string()) {
    const std::string untrusted = r["untrustedSegments"].get<std::string>();
    QualityFlag f{"Segments trusted", untrusted.empty(), ""};
    for (const char* seg : kSegments) {
      const json segment = r.value("segments", json::object()).value(seg, json());
      if (!segment.is_object() || !segment.contains("trusted")) continue;
      f.detail += std::string(seg) + (segment["trusted"].get<bool>() ? " yes" : " NO") + " (expected error " +
                  Fixed(Number(segment, "expectedErrorMm", 0.0), 1) + " mm), ";
    }
    f.detail += f.ok ? "findings carry reliable=false only where their bound exceeds " + Fixed(Number(r, "reliableBoundMm", 7.0), 0) + " mm"
                     : "findings on untrusted segments carry reliable=false";
    flags.push_back(f);
  }
  const int flips = static_cast<int>(Number(r, "flippedTriangles", -1.0));
  flags.push_back({"Registration one-to-one", flips == 0,
                   std::to_string(flips) + " flipped triangles in the composed map" +
                       (flips == 0 ? "" : ": findings near them may map to the wrong fold")});
  if (r.value("method", std::string()) != "harmonic") return;
  QualityFlag f{"Features matched per segment", true, ""};
  for (const char* seg : kSegments) {
    const json segment = r.value("segments", json::object()).value(seg, json());
    const int matched = static_cast<int>(Number(segment.is_object() ? segment.value("features", json::object()) : json(),
                                                "matched", 0.0));
    if (matched < t.minMatchedFeatures) f.ok = false;
    f.detail += std::string(seg) + " " + std::to_string(matched) + ", ";
  }
  f.detail += f.ok ? "matched fold pairs" : "matched fold pairs; segments with fewer than " +
                                                std::to_string(t.minMatchedFeatures) +
                                                " rely on the conformal map alone";
  flags.push_back(f);
}

}  // namespace

std::vector<QualityFlag> AssessQuality(const StageSummaries& s, const QualityThresholds& t) {
  std::vector<QualityFlag> flags;
  FlexureFlags(s, flags);
  TaeniaFlags(s, t, flags);
  LengthFlag(s, t, flags);
  JointFlexureFlag(s, t, flags);
  FlatteningFlags(s, t, flags);
  RegistrationFlags(s, t, flags);
  return flags;
}

}  // namespace colonmap::report
