// ColonEvaluateRegistration: a registration + corresponding supine/prone points -> errors in mm
// and in the flat domain, per segment and overall (issue 7, DESIGN §2.6). Thin: arguments,
// reading, Libs/Registration (transfer, statistics), writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/MarkupsIO.h"
#include "Registration/ErrorStatistics.h"
#include "Registration/PointTransfer.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace {

using namespace colonmap;
using namespace colonmap::registration;
namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kNames[5] = {"A", "T", "D", "S", "R"};

struct Group {
  std::vector<double> e3, flat, roundTrip, uncertainty;
  std::vector<bool> reliable;
};

json Summary(const std::vector<double>& e) {
  const ErrorSummary s = SummarizeErrors(e);
  return {{"count", s.count}, {"mean", s.mean}, {"median", s.median}, {"p90", s.p90}, {"max", s.max}};
}

std::string Segment(const std::string& description) {
  std::istringstream in(description);
  std::string w;
  while (in >> w)
    if (w.rfind("segment=", 0) == 0) return w.substr(8);
  return "";
}

// Flat position (u, v) of a point on `mesh` (face, bary) from the point array `name`, the face's
// corners unwrapped to the first one's period (u periodic with period 1).
Eigen::Vector2d FlatAt(const TriangleMesh& mesh, const std::string& name, int face, const Eigen::Vector3d& bary) {
  const Eigen::MatrixXd& uv = mesh.pointData.at(name).values;
  const Eigen::Vector2d a = uv.row(mesh.F(face, 0));
  Eigen::Vector2d r = bary(0) * a;
  for (int k = 1; k < 3; ++k) {
    Eigen::Vector2d b = uv.row(mesh.F(face, k));
    b.x() -= std::round(b.x() - a.x());
    r += bary(k) * b;
  }
  return r;
}

double FlatDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  double du = std::fabs(a.x() - b.x());
  du -= std::floor(du + 0.5);  // nearest period: |du| <= 0.5
  return std::hypot(du, a.y() - b.y());
}

double Correlation(const std::vector<double>& x, const std::vector<double>& y) {
  const std::size_t n = x.size();
  if (n < 2) return 0.0;
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < n; ++i) mx += x[i], my += y[i];
  mx /= n, my /= n;
  double sxy = 0, sxx = 0, syy = 0;
  for (std::size_t i = 0; i < n; ++i) {
    sxy += (x[i] - mx) * (y[i] - my);
    sxx += (x[i] - mx) * (x[i] - mx);
    syy += (y[i] - my) * (y[i] - my);
  }
  return sxx > 0 && syy > 0 ? sxy / std::sqrt(sxx * syy) : 0.0;
}

void Run(cli::ModuleContext& ctx) {
  const std::string reg = ctx.args.GetString("registration"), ts = ctx.args.GetString("truthSupine"),
                    tp = ctx.args.GetString("truthProne"), out = ctx.args.GetString("output");
  if (reg.empty()) throw Error("registration: no file given (--registration)");
  if (ts.empty() || tp.empty()) throw Error("truth points: both --truthSupine and --truthProne are needed");
  const std::string ps = ctx.args.GetString("polypsSupine"), pp = ctx.args.GetString("polypsProne");
  if (ps.empty() != pp.empty()) throw Error("polyps: give both --polypsSupine and --polypsProne, or neither");
  ctx.progress.Plan({{"Read", 1.0}, {"Evaluate", 1.0}, {"Write", 0.1}});
  ctx.progress.StartStage("Read", "reading the registration and the points");
  const MarkupList supinePoints = io::ReadMarkups(ts, "supine truth points"), pronePoints = io::ReadMarkups(tp, "prone truth points");
  MarkupList supinePolyps, pronePolyps;
  if (!ps.empty()) {
    supinePolyps = io::ReadMarkups(ps, "supine polyps");
    pronePolyps = io::ReadMarkups(pp, "prone polyps");
  }
  const RegistrationMeshes meshes = ReadRegistration(reg, ctx.args.GetString("proneMesh"));
  for (const char* a : {"ProneFlatUV"})
    if (!meshes.supine.pointData.count(a) || !meshes.prone.pointData.count(a))
      throw InputError("registration", reg, std::string("has no point data ") + a);
  const PointTransfer forward(meshes.supine, meshes.prone, "Prone", "registration '" + reg + "'");
  const PointTransfer backward(meshes.prone, meshes.supine, "Supine", "prone registration mesh");
  ctx.progress.EndStage();

  ctx.progress.StartStage("Evaluate", "transferring the supine points");
  std::map<std::string, Group> groups;  // "all", segment names, "polyps", "open" (with collapses)
  long unmatched = 0;
  // Collapsed stretches (phantom truth says collapsed=true|false per scan): the truth points on
  // wall open in the supine scan but collapsed in the prone one (a finding there has no prone
  // position) and how many of them the transfer flags visible=false; those collapsed in the
  // supine scan (inside a bridged stretch, or off the seen wall beside it) likewise; and open
  // points it flags wrongly.
  long proneOnly = 0, proneOnlyFlagged = 0, supineClosed = 0, supineClosedFlagged = 0, openHidden = 0;
  bool collapseTruth = false;
  json perPoint = json::array();
  auto evaluate = [&](const MarkupList& s, const MarkupList& p, bool polyps) {
    std::map<std::string, const ControlPoint*> byLabel;
    for (const ControlPoint& c : p.points) byLabel[c.label] = &c;
    for (std::size_t i = 0; i < s.points.size(); ++i) {
      const ControlPoint& c = s.points[i];
      const auto it = byLabel.find(c.label);
      if (it == byLabel.end()) {
        ++unmatched;
        continue;
      }
      const TransferredPoint t = forward.Transfer(c.position);
      const double e3 = (t.position - it->second->position).norm();
      // Flat error in the prone flat domain: the transferred foot vs the true point's foot.
      const Eigen::Vector2d flatMapped = FlatAt(meshes.supine, "ProneFlatUV", t.sourceFace, t.sourceBary);
      int face = 0;
      Eigen::Vector3d bary;
      forward.NearestOnTarget(it->second->position, &face, &bary);
      const Eigen::Vector2d flatTrue = FlatAt(meshes.prone, "ProneFlatUV", face, bary);
      const double ef = FlatDistance(flatMapped, flatTrue);
      const double rt = (backward.Transfer(t.position).position - c.position).norm();
      std::string seg = Segment(c.description);
      if (seg.empty() && t.segment >= 0 && t.segment < 5) seg = kNames[t.segment];
      json row = {{"label", c.label}, {"group", polyps ? "polyps" : seg}, {"error3D", e3}, {"errorFlat", ef},
                  {"roundTrip", rt}, {"uncertainty", t.uncertaintyMm}, {"uncertaintyMedian", t.uncertaintyMedianMm},
                  {"offset", t.offset}, {"dilatation", t.dilatation}, {"reliable", t.reliable},
                  {"mappedFlat", {flatMapped.x(), flatMapped.y()}}, {"trueFlat", {flatTrue.x(), flatTrue.y()}}};
      // The uncertainty's components where the registration has them (for calibration studies).
      for (const char* a : {"UncertaintyLoo", "UncertaintyNearMm", "UncertaintyCorrectionMm", "UncertaintyDilatation",
                            "UncertaintyFlexureMm", "UncertaintyCurvature", "UncertaintyScale",
                            "UncertaintyAlongMm"}) {
        const double v = forward.SourceValue(a, t);
        if (std::isfinite(v)) row[a] = v;
      }
      if (t.segment >= 0 && t.segment < 5) row["mapSegment"] = kNames[t.segment];
      row["visible"] = t.visible;
      const bool tagged = c.description.find("collapsed=") != std::string::npos;
      const bool supineShut = c.description.find("collapsed=true") != std::string::npos;
      const bool proneShut = it->second->description.find("collapsed=true") != std::string::npos;
      const bool closed = supineShut || proneShut;
      if (tagged) {
        collapseTruth = true;
        row["collapsedInTruth"] = supineShut ? (proneShut ? "both" : "supine") : (proneShut ? "prone" : "none");
        proneOnly += proneShut && !supineShut;
        proneOnlyFlagged += proneShut && !supineShut && !t.visible;
        supineClosed += supineShut;
        supineClosedFlagged += supineShut && !t.visible;
        openHidden += !closed && !t.visible;
      }
      if (const double v = forward.SourceValue("Trusted", t); std::isfinite(v)) row["trusted"] = v >= 0.5;  // the registration's segment at the foot
      perPoint.push_back(row);
      std::vector<std::string> into = polyps ? std::vector<std::string>{"polyps"} : std::vector<std::string>{"all", seg};
      if (tagged && !closed && !polyps) into.push_back("open");  // wall open in both scans
      for (const std::string& g : into) {
        if (g.empty()) continue;
        Group& G = groups[g];
        G.e3.push_back(e3);
        G.flat.push_back(ef);
        G.roundTrip.push_back(rt);
        G.uncertainty.push_back(t.uncertaintyMm);
        G.reliable.push_back(t.reliable);
      }
      if ((i & 63) == 0) ctx.progress.Report(static_cast<double>(i) / std::max<std::size_t>(1, s.points.size()));
    }
  };
  evaluate(supinePoints, pronePoints, false);
  if (!ps.empty()) evaluate(supinePolyps, pronePolyps, true);
  if (!groups.count("all")) throw InputError("supine truth points", ts, "no label in common with the prone truth points");
  ctx.progress.EndStage();

  ctx.progress.StartStage("Write", "writing the report");
  json report, segs;
  std::ostringstream tsv;
  tsv << "group\tcount\tmean_mm\tmedian_mm\tp90_mm\tmax_mm\tflat_mean\tflat_median\tflat_p90\tflat_max\troundtrip_mean_mm\n";
  auto row = [&](const std::string& name, const Group& g) {
    const ErrorSummary a = SummarizeErrors(g.e3), f = SummarizeErrors(g.flat), r = SummarizeErrors(g.roundTrip);
    char b[512];
    std::snprintf(b, sizeof b, "%s\t%ld\t%.3f\t%.3f\t%.3f\t%.3f\t%.5f\t%.5f\t%.5f\t%.5f\t%.4f\n", name.c_str(), a.count, a.mean,
                  a.median, a.p90, a.max, f.mean, f.median, f.p90, f.max, r.mean);
    tsv << b;
    // uncertainty is ColonTransferPoints' 90% bound: coverage should be about 0.9.
    // Of the points more than 20 mm off, the share the output warns about (a bound above 20 mm
    // or reliable=false): a large error must not come with a small promise.
    long covered = 0, large = 0, largeWarned = 0, unreliable = 0;
    for (std::size_t i = 0; i < g.e3.size(); ++i) {
      covered += g.e3[i] <= g.uncertainty[i];
      unreliable += !g.reliable[i];
      if (g.e3[i] > 20.0) {
        ++large;
        largeWarned += g.uncertainty[i] > 20.0 || !g.reliable[i];
      }
    }
    const double n = std::max<double>(1.0, static_cast<double>(g.e3.size()));
    return json{{"error3D", Summary(g.e3)},
                {"errorFlat", Summary(g.flat)},
                {"roundTrip", Summary(g.roundTrip)},
                {"uncertainty", {{"mean", SummarizeErrors(g.uncertainty).mean},
                                 {"coverage", g.e3.empty() ? 0.0 : static_cast<double>(covered) / g.e3.size()},
                                 {"correlationWithError", Correlation(g.uncertainty, g.e3)},
                                 {"unreliableFraction", static_cast<double>(unreliable) / n},
                                 {"above20mm", large},
                                 {"above20mmWarned", largeWarned}}}};
  };
  for (const char* X : kNames)
    if (groups.count(X)) segs[X] = row(X, groups[X]);
  report["overall"] = row("all", groups["all"]);
  report["segments"] = segs;
  if (groups.count("polyps")) report["polyps"] = row("polyps", groups["polyps"]);
  if (collapseTruth) {
    if (groups.count("open")) report["open"] = row("open", groups["open"]);
    report["collapsed"] = {{"proneOnly", proneOnly}, {"proneOnlyNotVisible", proneOnlyFlagged},
                           {"supine", supineClosed}, {"supineNotVisible", supineClosedFlagged},
                           {"openButNotVisible", openHidden},
                           {"note", "truth points on wall open in the supine scan and collapsed in the prone scan (proneOnly) "
                                    "and those the transfer marks visible=false; points collapsed in the supine scan (on its "
                                    "bridged wall or off the seen wall beside it) likewise; open points marked visible=false; 'open' holds the errors of the "
                                    "points open in both scans"}};
  }
  report["unmatchedLabels"] = unmatched;
  report["points"] = perPoint;  // per point: error, flat positions (mapped and true, prone FlatUV)
  report["flatWidth"] = 1.0;
  if (!out.empty()) {
    io::WriteText(report.dump(2) + "\n", ctx.outputs.Stage(out, "error report"), "error report");
    fs::path t = out;
    const std::string name = t.filename().string();
    const std::string base = name.size() > 5 && name.substr(name.size() - 5) == ".json" ? name.substr(0, name.size() - 5) : name;
    t.replace_filename(base + ".tsv");
    if (!ctx.args.GetString("outputTable").empty()) t = ctx.args.GetString("outputTable");
    io::WriteText(tsv.str(), ctx.outputs.Stage(t.string(), "error table"), "error table");
  } else {
    std::istringstream lines(tsv.str());
    for (std::string l; std::getline(lines, l);) ctx.progress.Note(l);
  }
  ctx.progress.EndStage();
  const ErrorSummary all = SummarizeErrors(groups["all"].e3);
  ctx.progress.Note("ColonEvaluateRegistration: " + std::to_string(all.count) + " points, 3D error mean " +
                    cli::FormatNumber(all.mean) + " mm, median " + cli::FormatNumber(all.median) + " mm, p90 " +
                    cli::FormatNumber(all.p90) + " mm, max " + cli::FormatNumber(all.max) + " mm");
  ctx.SetReturn("meanError", cli::FormatNumber(all.mean));
  ctx.SetReturn("medianError", cli::FormatNumber(all.median));
  ctx.SetReturn("p90Error", cli::FormatNumber(all.p90));
}

}  // namespace

COLONMAP_MODULE_BODY(ColonEvaluateRegistration, Run)
