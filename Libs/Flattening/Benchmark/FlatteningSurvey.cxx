// FlatteningSurvey: measures conformal flattening (issue 6) on many segments, with the mesh's
// own cotangent Laplacian and with the intrinsic Delaunay one, side by side: flipped triangles
// and where they lie, |mu|, time per step. Not a test; the figures go to docs/performance.md.
//
//   FlatteningSurvey [--json OUT.json] [--gca] [LANDMARKS_DIR ...]
//
// LANDMARKS_DIR: a ColonLandmarks output folder (segment_{A,T,D,S,R}.vtp, taeniae.vtp); each
// segment is prepared as ColonFlattening does (SplitBoundaryChords, cut along the IsCut taenia).
// --gca: the real colon of the Edinburgh Gut Cell Atlas (EdinGCA_3D_00020, CC BY 4.0), made
// genus 0 at 1.5 mm / 200K faces and split at our landmarks and at the atlas's own flexures,
// exactly as Testing/GcaFlatteningTest.cxx does.
// Per flipped face it records: a corner on an end loop, a corner on the cut path, its largest
// angle, and whether one of its edges has a negative cotangent weight on the mesh.
#include "Core/Error.h"
#include "Flattening/BeltramiCoefficient.h"
#include "Flattening/ConformalFlattening.h"
#include "Flattening/PrepareSegment.h"
#include "Flattening/SplitBoundaryChords.h"
#include "Surface/VtkConversion.h"
#include "IO/MeshIO.h"
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"

#include "Landmarks/ColonLandmarks.h"
#ifdef COLONMAP_SURVEY_GCA
#include "Analysis/GcaModel.h"
#endif

#include <Eigen/Geometry>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <chrono>
#include <set>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace {

using namespace colonmap;
using namespace colonmap::flattening;
namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kNames[5] = {"A", "T", "D", "S", "R"};

// The IsCut line of segment id from taeniae.vtp as segment vertex ids (VertexId point data).
Eigen::VectorXi CutPath(const PolylineSet& taeniae, int id) {
  const std::optional<landmarks::CutTaenia> cut = landmarks::CutTaeniaOf(taeniae, id);
  if (!cut) throw Error("no cut taenia for segment " + std::to_string(id));
  return cut->vertices;
}

// before = what ColonFlattening did until now; after = today's defaults.
// prepared: the mesh after PrepareSegment (else after SplitBoundaryChords only, as before).
struct Variant {
  const char* name;
  LaplacianMode laplacian;
  EndCondition ends;
  bool prepared;
};
const Variant kVariants[4] = {{"before", LaplacianMode::Mesh, EndCondition::Neumann, false},
                              {"idt-neumann", LaplacianMode::IntrinsicDelaunay, EndCondition::Neumann, true},
                              {"mesh-flux", LaplacianMode::Mesh, EndCondition::ConjugateFlux, false},
                              {"after", LaplacianMode::IntrinsicDelaunay, EndCondition::ConjugateFlux, true}};

// Largest distance from the drawn faces' edge midpoints and centroids to the input surface,
// over the faces not in the input (vtkStaticCellLocator).
double DrawnFaceGap(const TriangleMesh& mesh, const CutMesh& cut) {
  std::set<std::array<int, 3>> input;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    std::array<int, 3> t = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    std::sort(t.begin(), t.end());
    input.insert(t);
  }
  vtkNew<vtkPolyData> pd;
  surface::ToPolyData(mesh, pd);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(pd);
  locator->BuildLocator();
  double worst = 0.0;
  for (Eigen::Index f = 0; f < cut.F.rows(); ++f) {
    std::array<int, 3> t;
    for (int c = 0; c < 3; ++c) t[c] = cut.original(cut.F(f, c));
    std::array<int, 3> sorted = t;
    std::sort(sorted.begin(), sorted.end());
    if (input.count(sorted)) continue;
    const Eigen::Vector3d p[3] = {mesh.V.row(t[0]), mesh.V.row(t[1]), mesh.V.row(t[2])};
    const Eigen::Vector3d q[4] = {(p[0] + p[1]) / 2, (p[1] + p[2]) / 2, (p[2] + p[0]) / 2, (p[0] + p[1] + p[2]) / 3};
    for (const Eigen::Vector3d& x : q) {
      double closest[3], d2;
      vtkIdType cell;
      int sub;
      double xx[3] = {x.x(), x.y(), x.z()};
      locator->FindClosestPoint(xx, closest, cell, sub, d2);
      worst = std::max(worst, std::sqrt(d2));
    }
  }
  return worst;
}

json Measure(const TriangleMesh& mesh, const Eigen::VectorXi& path, const Eigen::VectorXd& arc, LaplacianMode mode,
             EndCondition ends) {
  FlatteningOptions o;
  o.laplacian = mode;
  o.ends = ends;
  NullProgress np;
  const auto t0 = std::chrono::steady_clock::now();
  const FlatteningResult r = ConformalFlattening(mesh.V, mesh.F, path, arc, o, np);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Eigen::VectorXcd mu = BeltramiCoefficient(r.cut.V, r.uv, r.cut.F);
  const DistortionStats q = SummarizeDistortion(r.cut.V, r.uv, r.cut.F, mu);
  json j;
  j["flips"] = q.flipped;
  j["muMean"] = q.muMean;
  j["muP99"] = q.muP99;
  j["muMax"] = q.muMax;
  j["seconds"] = seconds;
  j["edgeFlips"] = r.edgeFlips;
  j["negativeWeightsUsed"] = r.negativeWeightsUsed;
  j["nonPositiveFlux"] = r.nonPositiveFlux;
  j["negativeWeightsOnCut"] = r.negativeWeightsOnCut;
  j["changedFaces"] = r.changedFaces;
  j["edgeGapBound"] = r.edgeGapBound;
  if (r.changedFaces > 0) j["drawnFaceGap"] = DrawnFaceGap(mesh, r.cut);
  for (const auto& [step, s] : r.times) j["times"][step] = s;
  // Where the flipped faces are.
  if (q.flipped > 0) {
    std::vector<char> onLoop(mesh.V.rows(), 0), onPath(mesh.V.rows(), 0);
    for (int v : r.g1) onLoop[v] = 1;
    for (int v : r.g2) onLoop[v] = 1;
    for (Eigen::Index i = 0; i < path.size(); ++i) onPath[path(i)] = 1;
    const Eigen::SparseMatrix<double> L = surface::CotangentLaplacian(mesh.V, mesh.F);
    const Eigen::VectorXd flat = SignedFlatAreas(r.uv, r.cut.F);
    long loop = 0, cut = 0, negative = 0, obtuse = 0;
    json faces = json::array();
    // Faces of the drawn triangulation (r.cut.F: the mesh's, or the intrinsic Delaunay ones).
    for (Eigen::Index f = 0; f < r.cut.F.rows(); ++f) {
      if (flat(f) > 0) continue;
      bool l = false, c = false, neg = false;
      double maxAngle = 0;
      int loopCorners = 0;
      json uvs = json::array(), ws = json::array();
      for (int k = 0; k < 3; ++k) {
        const int a = r.cut.original(r.cut.F(f, k)), b = r.cut.original(r.cut.F(f, (k + 1) % 3)),
                  d = r.cut.original(r.cut.F(f, (k + 2) % 3));
        loopCorners += onLoop[a];
        uvs.push_back({r.uv(r.cut.F(f, k), 0), r.uv(r.cut.F(f, k), 1), onLoop[a],
                       (r.cut.V.row(r.cut.F(f, k)) - r.cut.V.row(r.cut.F(f, (k + 1) % 3))).norm()});
        ws.push_back(L.coeff(a, b));  // 0: not an edge of the mesh
        l = l || onLoop[a];
        c = c || onPath[a];
        neg = neg || L.coeff(a, b) < 0;
        const Eigen::Vector3d u = mesh.V.row(b) - mesh.V.row(a), w = mesh.V.row(d) - mesh.V.row(a);
        maxAngle = std::max(maxAngle, std::atan2(u.cross(w).norm(), u.dot(w)) * 180.0 / M_PI);
      }
      loop += l;
      cut += c;
      negative += neg;
      obtuse += maxAngle > 90.0;
      if (faces.size() < 20)
        faces.push_back({{"face", f}, {"onLoop", l}, {"onCut", c}, {"negativeWeight", neg}, {"maxAngleDeg", maxAngle},
                         {"muAbs", std::abs(mu(f))}, {"loopCorners", loopCorners}, {"uv", uvs}, {"meshWeights", ws}});
    }
    j["flipped"] = {{"onLoop", loop}, {"onCut", cut}, {"negativeWeightEdge", negative}, {"obtuse", obtuse},
                    {"first", faces}};
  }
  return j;
}

json Segment(const std::string& what, TriangleMesh mesh, const Eigen::VectorXi& inputPath) {
  TriangleMesh prepared = mesh;
  Eigen::VectorXi path = inputPath, preparedPath = inputPath;
  const int split = SplitBoundaryChords(mesh);  // appends vertices: the path's ids stay valid
  const PreparedSegment prep = PrepareSegment(prepared, preparedPath);
  Eigen::VectorXd arc;
  if (auto a = mesh.pointData.find("CenterlineArcLength"); a != mesh.pointData.end()) arc = a->second.values.col(0);
  json j;
  j["what"] = what;
  j["faces"] = mesh.F.rows();
  j["chordsSplit"] = split;
  j["keptEdgesSplit"] = prep.splitEdges;
  j["negativeLeft"] = prep.negativeLeft;
  {
    // Share of the mesh's interior edges with a negative cotangent weight.
    const Eigen::SparseMatrix<double> L = surface::CotangentLaplacian(mesh.V, mesh.F);
    long neg = 0;
    for (int c = 0; c < L.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it)
        if (it.row() < c && it.value() < 0) ++neg;
    j["negativeWeightEdges"] = neg;
  }
  std::printf("%-28s %7ld faces, %5ld negative weights:", what.c_str(), static_cast<long>(mesh.F.rows()),
              j["negativeWeightEdges"].get<long>());
  for (const Variant& v : kVariants) {
    if (v.prepared) {
      Eigen::VectorXd parc;
      if (auto a = prepared.pointData.find("CenterlineArcLength"); a != prepared.pointData.end()) parc = a->second.values.col(0);
      j[v.name] = Measure(prepared, preparedPath, parc, v.laplacian, v.ends);
    } else {
      j[v.name] = Measure(mesh, path, arc, v.laplacian, v.ends);
    }
    const json& m = j[v.name];
    std::printf(" | %s %3ld %.4f %.2f", v.name, m["flips"].get<long>(), m["muMean"].get<double>(), m["seconds"].get<double>());
  }
  std::printf(" | kept edges split %d (left %d), after: %ld faces changed, gap bound %.3f, measured %.3f mm\n",
              prep.splitEdges, prep.negativeLeft, j["after"]["changedFaces"].get<long>(), j["after"]["edgeGapBound"].get<double>(),
              j["after"].value("drawnFaceGap", 0.0));
  for (const Variant& v : kVariants)
    if (j[v.name].contains("flipped")) {
      const json& x = j[v.name]["flipped"];
      std::printf("    %s flips: on loop %ld, on cut %ld, with a negative-weight edge %ld, obtuse %ld\n", v.name,
                  x["onLoop"].get<long>(), x["onCut"].get<long>(), x["negativeWeightEdge"].get<long>(), x["obtuse"].get<long>());
    }
  std::fflush(stdout);
  return j;
}

#ifdef COLONMAP_SURVEY_GCA
void GcaSegments(const char* what, const landmarks::ColonSegments& segs, const std::vector<landmarks::Taenia>& taeniae,
                 json& out) {
  for (int s = 0; s < 5; ++s)
    for (const auto& t : taeniae)
      if (t.segment == s && t.isCut) {
        Eigen::VectorXi path(static_cast<Eigen::Index>(t.vertices.size()));
        for (std::size_t i = 0; i < t.vertices.size(); ++i) path(static_cast<Eigen::Index>(i)) = t.vertices[i];
        out.push_back(Segment(std::string("gca ") + what + " " + kNames[s], segs.segment[s], path));
      }
}

void Gca(json& out) {
  const std::string dir = std::string(COLONMAP_SHARED_DIR) + "/data/gca-00020";
  const analysis::GcaModel g = analysis::ReadGcaModel(dir);
  const analysis::GcaGenusZero colon = analysis::GenusZeroGcaColon(analysis::WeldGcaColon(g), 1.5, 200000);
  NullProgress np;
  const landmarks::LandmarkResult r = landmarks::FindLandmarks(colon.colon, {}, np);
  GcaSegments("found", r.segments, r.taeniae, out);
  const char* atlas[3] = {"HF", "SF", "DSJ"};
  std::array<double, 4> arcs{};
  for (int k = 0; k < 3; ++k) {
    const Eigen::MatrixXd p = g.midline.row(g.landmark.at(atlas[k]));
    arcs[static_cast<std::size_t>(k)] = landmarks::NearestArcLength(p, r.centerline.points)(0);
  }
  arcs[3] = r.flexures.arc[3];
  const landmarks::ColonSegments segs = landmarks::SplitColon(colon.colon, r.alongColon, r.centerline.points, r.centerline.arc, arcs, {}, np);
  GcaSegments("atlas", segs, landmarks::FindTaeniae(segs, r.centerline.points, {}, np), out);
}
#endif

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string jsonPath;
    bool gca = false;
    std::vector<std::string> dirs;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--json" && i + 1 < argc) jsonPath = argv[++i];
      else if (a == "--gca") gca = true;
      else dirs.push_back(a);
    }
    json out = json::array();
    for (const std::string& d : dirs) {
      const PolylineSet taeniae = io::ReadPolylines((fs::path(d) / "taeniae.vtp").string(), "taeniae");
      for (int id = 0; id < 5; ++id) {
        const fs::path p = fs::path(d) / ("segment_" + std::string(kNames[id]) + ".vtp");
        if (!fs::exists(p)) continue;
        out.push_back(Segment(d + " " + kNames[id], io::ReadMesh(p.string(), "segment"), CutPath(taeniae, id)));
      }
    }
    if (gca) {
#ifdef COLONMAP_SURVEY_GCA
      Gca(out);
#else
      throw Error("built without the GCA model");
#endif
    }
    // Totals per mode.
    for (const Variant& v : kVariants) {
      const char* mode = v.name;
      long flips = 0, flippedSegments = 0;
      double worstMu = 0, seconds = 0;
      for (const auto& s : out) {
        flips += s[mode]["flips"].get<long>();
        flippedSegments += s[mode]["flips"].get<long>() > 0;
        worstMu = std::max(worstMu, s[mode]["muMean"].get<double>());
        seconds += s[mode]["seconds"].get<double>();
      }
      std::printf("%s: %zu segments, %ld flipped faces in %ld segments, worst mean |mu| %.4f, %.2f s in all\n", mode,
                  out.size(), flips, flippedSegments, worstMu, seconds);
    }
    if (!jsonPath.empty()) std::ofstream(jsonPath) << out.dump(1) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "FlatteningSurvey: " << e.what() << "\n";
    return 1;
  }
}
