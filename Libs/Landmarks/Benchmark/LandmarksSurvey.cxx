// LandmarksSurvey: the landmark stage (issue 5) on phantom pairs through our own CT pipeline,
// against the phantom's truth. Not a test; the figures go to the README.
//
//   LandmarksSurvey [--json OUT.json] SEED_DIR ...
//
// SEED_DIR: a folder of scripts/registration_seeds.py's cache (surface/{supine,prone}_surface.vtp
// and phantom/ with {scan}_centerline.mrk.json, {scan}_flexures.mrk.json, {scan}_taeniae.vtp).
// Per scan: centreline length against the truth's and its mean distance from the true axis; each
// flexure's offset along the true centreline (and the DSJ's from the bottom of the true descent);
// per segment A, T, D the fraction of the cut taenia
// within 8 mm (3D) of the true band of the same name, over the true band's extent (points whose
// nearest true point is an end of the true band lie beyond it: our A segment goes on over the
// caecal pole), and the true band the found one lies closest to (its name should be the same).
#include "Analysis/MidlineProjection.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Landmarks/ColonLandmarks.h"

#include <nlohmann/json.hpp>

#include <cstdio>
#include <fstream>
#include <map>

using namespace colonmap;
using namespace colonmap::landmarks;

namespace {

// Fraction of `points` within 8 mm of `band`, over the band's extent.
double Coverage(const Eigen::MatrixXd& points, const Eigen::MatrixXd& band) {
  int near = 0, counted = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    Eigen::Index k = 0;
    const double d = (band.rowwise() - points.row(i)).rowwise().norm().minCoeff(&k);
    if (k == 0 || k == band.rows() - 1) continue;
    ++counted;
    near += d < 8.0;
  }
  return counted ? static_cast<double>(near) / counted : 0.0;
}

nlohmann::json Survey(const std::string& dir, const std::string& scan) {
  const TriangleMesh surface = io::ReadMesh(dir + "/surface/" + scan + "_surface.vtp", "surface");
  const PolylineSet truth = io::ReadPolylines(dir + "/phantom/" + scan + "_taeniae.vtp", "true taeniae");
  const Eigen::MatrixXd axis = Positions(io::ReadMarkups(dir + "/phantom/" + scan + "_centerline.mrk.json", "true centreline"));
  const MarkupList flexures = io::ReadMarkups(dir + "/phantom/" + scan + "_flexures.mrk.json", "true flexures");
  NullProgress none;
  const LandmarkResult r = FindLandmarks(surface, {}, none);
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  nlohmann::json j;
  const Eigen::VectorXd arc = analysis::ArcLength(axis);
  j["centerlineMm"] = r.centerline.Length();
  j["trueCenterlineMm"] = arc(arc.size() - 1);
  j["meanDistanceFromTrueAxisMm"] = analysis::ProjectToMidline(r.centerline.points, axis, po).distance.mean();
  // Arcs along the true axis: the true flexures' and ours.
  const auto onAxis = [&](const Eigen::Vector3d& p) { return analysis::ProjectToMidline(p.transpose(), axis, po).arc(0); };
  std::map<std::string, double> trueArc;
  for (const ControlPoint& p : flexures.points) trueArc[p.label] = onAxis(p.position);
  for (int k = 0; k < 4; ++k)
    if (trueArc.count(Flexures::Names()[k]))
      j["flexureOffsetMm"][Flexures::Names()[k]] = onAxis(r.flexures.position[k]) - trueArc[Flexures::Names()[k]];
  // The DSJ as the atlases place it (Flexures.h): the bottom of the descent, the lowest axis point
  // between the true SF and RSJ (the phantom's own DSJ lies 60-80 mm above it).
  if (trueArc.count("SF") && trueArc.count("RSJ")) {
    const Eigen::Index bottom = LowestBetween(axis, arc, trueArc["SF"], trueArc["RSJ"]);
    if (bottom >= 0) j["dsjFromBottomOfDescentMm"] = onAxis(r.flexures.position[2]) - arc(bottom);
  }
  for (const Taenia& t : r.taeniae) {
    if (!t.isCut || t.segment > 2) continue;
    const TriangleMesh& seg = r.segments.segment[t.segment];
    Eigen::MatrixXd P(static_cast<Eigen::Index>(t.vertices.size()), 3);
    for (std::size_t i = 0; i < t.vertices.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = seg.V.row(t.vertices[i]);
    std::map<std::string, double> cover;
    for (const Polyline& band : truth.lines) cover[band.name] = Coverage(P, band.points);
    std::string closest = t.name;
    for (const auto& [name, c] : cover)
      if (c > cover[closest]) closest = name;
    j["cutTaenia"][SegmentName(t.segment)] = {{"name", t.name}, {"coverage", cover[t.name]}, {"closestTrueBand", closest}};
  }
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  std::string jsonPath;
  nlohmann::json all = nlohmann::json::object();
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--json" && i + 1 < argc) {
      jsonPath = argv[++i];
      continue;
    }
    for (const std::string scan : {"supine", "prone"}) {
      try {
        const nlohmann::json j = Survey(a, scan);
        all[a][scan] = j;
        std::printf("%s %-6s centreline %.0f / %.0f mm, %.1f mm off the axis; flexures", a.c_str(), scan.c_str(),
                    j["centerlineMm"].get<double>(), j["trueCenterlineMm"].get<double>(),
                    j["meanDistanceFromTrueAxisMm"].get<double>());
        for (const auto& [name, d] : j["flexureOffsetMm"].items()) std::printf(" %s %+.0f", name.c_str(), d.get<double>());
        if (j.contains("dsjFromBottomOfDescentMm"))
          std::printf(" (DSJ from the bottom of the descent %+.0f)", j["dsjFromBottomOfDescentMm"].get<double>());
        std::printf("; cut taenia");
        for (const auto& [seg, t] : j["cutTaenia"].items())
          std::printf(" %s %.0f%%%s", seg.c_str(), 100 * t["coverage"].get<double>(),
                      t["closestTrueBand"] != t["name"] ? (" (is " + t["closestTrueBand"].get<std::string>() + ")").c_str() : "");
        std::printf("\n");
      } catch (const std::exception& e) {
        std::fprintf(stderr, "%s %s: %s\n", a.c_str(), scan.c_str(), e.what());
        return 1;
      }
    }
  }
  if (!jsonPath.empty()) std::ofstream(jsonPath) << all.dump(1) << "\n";
  return 0;
}
