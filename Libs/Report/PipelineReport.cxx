#include "Report/PipelineReport.h"

#include "Report/HtmlReport.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace colonmap::report {
namespace {

using nlohmann::json;
namespace fs = std::filesystem;

const char* const kSegments[5] = {"A", "T", "D", "S", "R"};
const char* const kSegmentNames[5] = {"ascending", "transverse", "descending", "sigmoid", "rectum"};

std::string Fixed(double v, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", digits, v);
  return buffer;
}

std::string Num(const json& j, const char* key, int digits) {
  return j.is_object() && j.contains(key) && j[key].is_number() ? Fixed(j[key].get<double>(), digits) : "-";
}

std::string Folder(const PipelineReportInput& in, const std::string& stage) {
  const auto it = in.folders.find(stage);
  return it == in.folders.end() ? std::string() : it->second;
}

void Flags(const PipelineReportInput& in, HtmlReport& page) {
  page.Heading("Quality");
  int warnings = 0;
  for (const auto& f : in.flags) warnings += f.ok ? 0 : 1;
  if (warnings > 0)
    page.Warning(std::to_string(warnings) + " quality check(s) need a look before the registration is trusted "
                 "(marked CHECK below).");
  for (const auto& f : in.flags) page.Flag(f.ok, f.name, f.detail);
  for (const auto& note : in.summary.value("notes", json::array())) page.Warning(note.get<std::string>());
}

void StatsRow(const std::string& name, const json& e, std::vector<std::vector<std::string>>& rows) {
  const json d = e.value("error3D", json::object());
  const json f = e.value("errorFlat", json::object());
  rows.push_back({name, Num(d, "count", 0), Num(d, "mean", 2), Num(d, "median", 2), Num(d, "p90", 2),
                  Num(d, "max", 2), Num(f, "mean", 4), Num(e.value("roundTrip", json::object()), "mean", 3)});
}

void Accuracy(const PipelineReportInput& in, HtmlReport& page) {
  const std::string dir = Folder(in, "evaluation");
  if (dir.empty()) return;
  const json errors = ReadJsonOrNull((fs::path(dir) / "errors.json").string());
  if (errors.is_null()) return;
  page.Heading("Registration error against the ground truth");
  page.Paragraph("3D distance (mm) on the prone wall between where the registration sends each supine "
                 "evaluation point and where it truly is; flat error in the flattened domain (width 1); "
                 "round trip: supine -> prone -> supine.");
  std::vector<std::vector<std::string>> rows;
  StatsRow("all points", errors.value("overall", json::object()), rows);
  for (const char* seg : kSegments) {
    const json s = errors.value("segments", json::object()).value(seg, json());
    if (s.is_object()) StatsRow(std::string("segment ") + seg, s, rows);
  }
  if (errors.contains("polyps")) StatsRow("polyps", errors["polyps"], rows);
  page.Table({"points", "n", "mean mm", "median mm", "p90 mm", "max mm", "flat mean", "round trip mm"}, rows);
}

std::string MorphName(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "morph_%03d.png", frame);
  return name;
}

void FlatViews(const PipelineReportInput& in, HtmlReport& page) {
  const std::string dir = Folder(in, "flatviews");
  if (dir.empty()) return;
  const auto image = [&](const char* file, const char* caption) {
    page.Image((fs::path(dir) / file).string(), caption);
  };
  page.Heading("Flattened colon, supine and prone");
  image("flat_pair_unregistered.png",
        "Mean-curvature images of the five flattened segments, supine (left) and prone (right), each in its "
        "own conformal coordinates (before registration)");
  image("flat_pair_registered.png",
        "After registration: the prone image resampled into the supine coordinates, so the same (u, v) is the "
        "same anatomy");
  image("features_matched.png", "Haustral fold features; matched pairs share a colour, unmatched ones are grey");
  page.Heading("Distortion of the registration");
  image("dilatation_flat.png", "Dilatation K = (1 + |mu|) / (1 - |mu|) on the supine flat domain (1: conformal)");
  image("angle_flat.png", "Angle theta = arg(mu) / 2 of the stretch direction");
  image("checkerboard_pair.png", "A checkerboard on the supine flat domain and as carried to the prone one");
  image("circles_pair.png", "Circles on the supine flat domain and as carried to the prone one");
  // 3D renderings exist only where ColonFlatViews had a display.
  const auto optional = [&](const char* file, const char* caption) {
    if (fs::exists(fs::path(dir) / file)) image(file, caption);
  };
  optional("distortion_3d.png", "Dilatation K and angle theta on the supine colon surface");
  optional("textures_3d.png",
           "Checkerboard (top) and circles (bottom); on the supine surface (left), carried onto the prone one (right)");
  for (int frame = 0; fs::exists(fs::path(dir) / "morph" / MorphName(frame)); ++frame)
    image(("morph/" + MorphName(frame)).c_str(),
          ("Morph from supine to prone geometry, frame " + std::to_string(frame)).c_str());
}

void Findings(const PipelineReportInput& in, HtmlReport& page) {
  const json transferred = in.summary.value("findings", json::array());
  if (transferred.empty()) return;
  page.Heading("Findings carried from supine to prone");
  std::vector<std::vector<std::string>> rows;
  for (const auto& f : transferred) {
    const auto vec = [&](const char* key) {
      const json p = f.value(key, json::array());
      return p.size() == 3 ? Fixed(p[0].get<double>(), 1) + ", " + Fixed(p[1].get<double>(), 1) + ", " +
                                 Fixed(p[2].get<double>(), 1)
                           : std::string("-");
    };
    rows.push_back({f.value("label", std::string()), vec("supine"), vec("prone"), f.value("segment", std::string("-")),
                    Num(f, "uncertaintyMm", 1),
                    !f.value("visible", true)
                        ? "NO: on wall collapsed in the " + f.value("notSeenIn", std::string("prone")) + " scan" +
                              (f.contains("alongColonToOpenMm") ? " (placed at the nearest open wall, " + Num(f, "alongColonToOpenMm", 0) +
                                                                      " mm along the colon)"
                                                                : std::string())
                    : f.contains("reliable") ? (f["reliable"].get<bool>() ? "yes" : "NO: do not rely on this position")
                                             : "-",
                    Num(f, "trueErrorMm", 1)});
  }
  page.Table({"finding", "supine LPS mm", "prone LPS mm", "segment", "90% bound mm", "reliable", "true error mm"}, rows);
  const std::string views = Folder(in, "views");
  if (views.empty()) return;
  page.Heading("Linked endoluminal views");
  for (const auto& f : transferred) {
    const std::string label = f.value("label", std::string());
    page.Image((fs::path(views) / ("view_" + label + ".png")).string(),
               "Finding " + label + ": supine view (left) and the prone view linked to it (right)");
  }
}

void Segments(const PipelineReportInput& in, HtmlReport& page) {
  const json& l0 = in.stages.landmarks[0];
  const json& l1 = in.stages.landmarks[1];
  if (l0.is_null() || l1.is_null()) return;
  page.Heading("Segments");
  std::vector<std::vector<std::string>> rows;
  for (int k = 0; k < 5; ++k) {
    const char* seg = kSegments[k];
    const json a = l0.value("segments", json::object()).value(seg, json());
    const json b = l1.value("segments", json::object()).value(seg, json());
    const json fa = in.stages.flattening[0].value("segments", json::object()).value(seg, json());
    const json fb = in.stages.flattening[1].value("segments", json::object()).value(seg, json());
    const json r = in.stages.registration.is_object()
                       ? in.stages.registration.value("segments", json::object()).value(seg, json())
                       : json();
    const json features = r.is_object() ? r.value("features", json()) : json();
    const json k3 = r.is_object() ? r.value("dilatation", json()) : json();
    // Expected error (median of the model over the segment) and whether it is trusted, with why not.
    std::string trusted = "-";
    if (r.is_object() && r.contains("trusted")) {
      trusted = r["trusted"].get<bool>() ? "yes" : "NO";
      for (const auto& why : r.value("untrustedBecause", json::array())) trusted += ": " + why.get<std::string>();
    }
    rows.push_back({std::string(seg) + " (" + kSegmentNames[k] + ")", Num(a, "lengthMm", 0), Num(b, "lengthMm", 0),
                    Num(a, "faces", 0), Num(b, "faces", 0),
                    Num(fa.is_object() ? fa.value("beltramiAbs", json()) : json(), "mean", 3),
                    Num(fb.is_object() ? fb.value("beltramiAbs", json()) : json(), "mean", 3),
                    Num(features, "matched", 0), Num(k3, "mean", 2), Num(k3, "p99", 2), Num(r, "expectedErrorMm", 1),
                    trusted});
  }
  page.Table({"segment", "length supine mm", "length prone mm", "faces supine", "faces prone", "mean |mu| supine",
              "mean |mu| prone", "features matched", "mean K", "p99 K", "expected error mm", "trusted"},
             rows);
}

std::string JoinNumbers(const json& list, int digits) {
  std::string out;
  for (const auto& v : list) out += (out.empty() ? "" : ", ") + Fixed(v.get<double>(), digits);
  return out.empty() ? "-" : out;
}

void Pieces(const PipelineReportInput& in, HtmlReport& page) {
  const json pieces = PiecesSummary(in.summary.value("stages", json::array()), in.stages.registration);
  if (pieces.is_null()) return;
  std::vector<std::vector<std::string>> rows;
  for (const char* scan : {"supine", "prone"}) {
    if (!pieces.contains(scan)) continue;
    const json& p = pieces[scan];
    std::string unseen;
    for (const auto& [seg, f] : p["wallNotSeen"].items())
      unseen += (unseen.empty() ? "" : ", ") + seg + " " + Fixed(100.0 * f.get<double>(), 0) + "%";
    rows.push_back({std::string(scan), std::to_string(p["pieces"].get<int>()), JoinNumbers(p["pieceLengthsMm"], 0),
                    JoinNumbers(p["gapsBridgedMm"], 0), Fixed(p["virtualLumenMl"].get<double>(), 1),
                    unseen.empty() ? "-" : unseen});
  }
  page.Heading("Colon pieces and collapsed stretches");
  page.Paragraph("A collapsed stretch splits the air of the colon into pieces. The segmentation ordered the pieces "
                 "from the caecum and bridged each gap with virtual lumen; the wall of that lumen was not seen in the "
                 "CT, and findings that land on it are marked visible=false and placed at the nearest open wall.");
  page.Table({"scan", "pieces", "piece lengths mm (from the caecum)", "gaps bridged mm", "virtual lumen ml",
              "wall not seen, per segment"},
             rows);
}

void Times(const PipelineReportInput& in, HtmlReport& page) {
  page.Heading("Stage times");
  std::vector<std::vector<std::string>> rows;
  for (const auto& s : in.summary.value("stages", json::array()))
    rows.push_back({s.value("name", std::string()), s.value("module", std::string()), Num(s, "seconds", 2)});
  // Stages run side by side (the two scans', the two views'): their own times overlap, the
  // block's is the wait.
  for (const auto& b : in.summary.value("stageBlocks", json::array()))
    if (b.value("sideBySide", false))
      rows.push_back({b.value("name", std::string()) + " (side by side)", "ColonSupineProne", Num(b, "seconds", 2)});
  rows.push_back({"whole pipeline", "ColonSupineProne", Num(in.summary, "totalSeconds", 2)});
  page.Table({"stage", "module", "seconds"}, rows);
}

}  // namespace

json ReadJsonOrNull(const std::string& path) {
  std::ifstream in(path);
  if (!in) return json();
  try {
    return json::parse(in);
  } catch (const json::exception&) {
    return json();
  }
}

json PiecesSummary(const json& stages, const json& registration) {
  // Comma-separated numbers of a return parameter ("729,160,230"; empty for one piece).
  const auto numbers = [](const std::string& text) {
    json out = json::array();
    std::size_t start = 0;
    while (start < text.size()) {
      const std::size_t end = std::min(text.find(',', start), text.size());
      try {
        out.push_back(std::stod(text.substr(start, end - start)));
      } catch (const std::exception&) {
      }
      start = end + 1;
    }
    return out;
  };
  json out = json::object();
  bool collapsed = false;
  for (const char* scan : {"supine", "prone"}) {
    json results;
    for (const auto& s : stages)
      if (s.value("name", std::string()) == std::string("segmentation ") + scan) results = s.value("results", json::object());
    if (!results.is_object() || results.empty()) continue;
    const json lengths = numbers(results.value("pieceLengths", std::string()));
    const int pieces = std::max<int>(1, static_cast<int>(lengths.size()));
    collapsed = collapsed || pieces > 1;
    json unseen = json::object();
    for (const char* seg : kSegments) {
      const json segment = registration.is_object() ? registration.value("segments", json::object()).value(seg, json()) : json();
      const double f = segment.is_object() ? segment.value(std::string(scan) + "VirtualFraction", 0.0) : 0.0;
      if (f > 0.0) unseen[seg] = f;
    }
    const json volume = numbers(results.value("virtualVolume", std::string("0")));
    out[scan] = {{"pieces", pieces},
                 {"pieceLengthsMm", lengths},
                 {"gapsBridgedMm", numbers(results.value("pieceGaps", std::string()))},
                 {"virtualLumenMl", volume.empty() ? 0.0 : volume[0].get<double>()},
                 {"wallNotSeen", unseen}};
  }
  return collapsed ? out : json();
}

std::string PipelineReportHtml(const PipelineReportInput& in) {
  HtmlReport page("ColonMap: supine-prone registration report");
  const json inputs = in.summary.value("inputs", json::object());
  page.Paragraph("Supine: " + inputs.value("supine", std::string("?")) + ". Prone: " +
                 inputs.value("prone", std::string("?")) + ". Registration method: " +
                 in.summary.value("method", std::string("?")) + ".");
  Flags(in, page);
  Accuracy(in, page);
  Findings(in, page);
  FlatViews(in, page);
  Segments(in, page);
  Pieces(in, page);
  Times(in, page);
  page.Heading("About");
  page.Paragraph("ColonMap registers the supine and prone colon walls by quasi-conformal mapping of the flattened "
                 "segments after W. Zeng, J. Marino, K. C. Gurijala, X. Gu and A. Kaufman, Supine and prone colon "
                 "registration using quasi-conformal mapping, IEEE TVCG 16(6), 2010. Research software: not for "
                 "clinical use. Files: registration.vtp (give it to ColonTransferPoints to carry more findings), "
                 "summary.json (stage times, results and these flags), one folder per stage.");
  return page.Html();
}

}  // namespace colonmap::report
