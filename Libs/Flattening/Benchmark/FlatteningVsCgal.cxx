// FlatteningVsCgal: our conformal flattening against CGAL's Surface_mesh_parameterization LSCM
// (least squares conformal maps, Levy et al. 2002; Debian libcgal-dev, header-only) on the same
// cut segment, in one run (issue 6). Not a test and not built by default (CGAL is slow to
// compile): `ninja FlatteningVsCgal`.
//
//   FlatteningVsCgal [--json OUT.json] [--runs N] [--phantom SPACING AROUND SEED] [DIR SEGMENT ...]
//
// DIR SEGMENT: a ColonLandmarks folder and a segment letter (A, T, D, S, R). --phantom: the
// phantom's true-wall T segment at that density (e.g. 1 160 2: 117K faces; see
// Libs/Flattening/Testing/PhantomSegments.h), cut along its taenia TO.
// Per segment: ours = PrepareSegment + ConformalFlattening with the defaults (what ColonFlattening
// runs; times per step); CGAL = LSCM with its default two fixed border vertices and its default
// solver, on the disk CutAlongPath gives (the mesh after SplitBoundaryChords, cut along the same
// path). Both: wall time (median of N runs, one thread each as built), flipped faces, |mu|
// (mean, p99, max) measured by the same code (Flattening/BeltramiCoefficient.h).
#include "Core/Error.h"
#include "Flattening/BeltramiCoefficient.h"
#include "Landmarks/ColonLandmarks.h"
#include "Flattening/ConformalFlattening.h"
#include "Flattening/CutAlongPath.h"
#include "Flattening/PrepareSegment.h"
#include "Flattening/SplitBoundaryChords.h"
#include "IO/MeshIO.h"
#include "PhantomSegments.h"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_parameterization/Error_code.h>
#include <CGAL/Surface_mesh_parameterization/LSCM_parameterizer_3.h>
#include <CGAL/Surface_mesh_parameterization/parameterize.h>
#include <CGAL/Polygon_mesh_processing/measure.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
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
namespace SMP = CGAL::Surface_mesh_parameterization;
using nlohmann::json;
using Kernel = CGAL::Simple_cartesian<double>;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using VertexIndex = Mesh::Vertex_index;
using Clock = std::chrono::steady_clock;

double Seconds(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

json Quality(const Eigen::MatrixXd& V, const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F) {
  const DistortionStats q = SummarizeDistortion(V, uv, F, BeltramiCoefficient(V, uv, F));
  return {{"flips", q.flipped}, {"muMean", q.muMean}, {"muP99", q.muP99}, {"muMax", q.muMax},
          {"logAreaRatioStd", q.logAreaRatioStd}};
}

Eigen::VectorXi CutPathFromTaeniae(const PolylineSet& taeniae, int id) {
  const std::optional<landmarks::CutTaenia> cut = landmarks::CutTaeniaOf(taeniae, id);
  if (!cut) throw Error("no cut taenia for segment " + std::to_string(id));
  return cut->vertices;
}

json Compare(const std::string& what, const TriangleMesh& input, const Eigen::VectorXi& inputPath, int runs) {
  json j;
  j["what"] = what;
  j["faces"] = input.F.rows();
  // Ours, as ColonFlattening runs it (preparation included in the time).
  std::vector<double> ours, prep;
  FlatteningResult r;
  TriangleMesh mesh;
  for (int k = 0; k < runs; ++k) {
    const Clock::time_point t0 = Clock::now();
    mesh = input;
    Eigen::VectorXi path = inputPath;
    PrepareSegment(mesh, path);
    prep.push_back(Seconds(t0));
    Eigen::VectorXd arc;
    if (auto a = mesh.pointData.find("CenterlineArcLength"); a != mesh.pointData.end()) arc = a->second.values.col(0);
    NullProgress np;
    r = ConformalFlattening(mesh.V, mesh.F, path, arc, FlatteningOptions{}, np);
    ours.push_back(Seconds(t0));
  }
  j["ours"] = Quality(r.cut.V, r.uv, r.cut.F);
  j["ours"]["seconds"] = Median(ours);
  j["ours"]["prepareSeconds"] = Median(prep);
  for (const auto& [step, s] : r.times) j["ours"]["times"][step] = s;

  // CGAL LSCM on the disk cut along the same path.
  TriangleMesh chords = input;
  SplitBoundaryChords(chords);
  const CutMesh disk = CutAlongPath(chords.V, chords.F, inputPath);
  std::vector<double> cgal, build;
  Eigen::MatrixXd uv(disk.V.rows(), 2);
  std::string status;
  for (int k = 0; k < runs; ++k) {
    const Clock::time_point t0 = Clock::now();
    Mesh sm;
    std::vector<VertexIndex> vs(static_cast<std::size_t>(disk.V.rows()));
    for (Eigen::Index v = 0; v < disk.V.rows(); ++v) vs[v] = sm.add_vertex(Kernel::Point_3(disk.V(v, 0), disk.V(v, 1), disk.V(v, 2)));
    for (Eigen::Index f = 0; f < disk.F.rows(); ++f)
      if (sm.add_face(vs[disk.F(f, 0)], vs[disk.F(f, 1)], vs[disk.F(f, 2)]) == Mesh::null_face())
        throw Error("CGAL refused face " + std::to_string(f));
    const auto bhd = CGAL::Polygon_mesh_processing::longest_border(sm).first;
    auto uvmap = sm.add_property_map<VertexIndex, Kernel::Point_2>("v:uv").first;
    build.push_back(Seconds(t0));
    const Clock::time_point t1 = Clock::now();
    const SMP::Error_code err = SMP::parameterize(sm, SMP::LSCM_parameterizer_3<Mesh>(), bhd, uvmap);
    cgal.push_back(Seconds(t1));
    status = SMP::get_error_message(err);
    for (Eigen::Index v = 0; v < disk.V.rows(); ++v) uv.row(v) << uvmap[vs[v]].x(), uvmap[vs[v]].y();
  }
  j["cgal"] = Quality(disk.V, uv, disk.F);
  j["cgal"]["seconds"] = Median(cgal);
  j["cgal"]["buildSeconds"] = Median(build);
  j["cgal"]["status"] = status;
  j["timeRatio"] = Median(cgal) / Median(ours);
  std::printf("%-34s %7ld faces | ours %.3f s (prepare %.3f), flips %ld, |mu| mean %.4f p99 %.3f | CGAL LSCM %.3f s "
              "(+ mesh %.3f), flips %ld, |mu| mean %.4f p99 %.3f (%s) | CGAL / ours %.1f\n",
              what.c_str(), static_cast<long>(input.F.rows()), Median(ours), Median(prep), j["ours"]["flips"].get<long>(),
              j["ours"]["muMean"].get<double>(), j["ours"]["muP99"].get<double>(), Median(cgal), Median(build),
              j["cgal"]["flips"].get<long>(), j["cgal"]["muMean"].get<double>(), j["cgal"]["muP99"].get<double>(),
              status.c_str(), j["timeRatio"].get<double>());
  std::fflush(stdout);
  return j;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    std::string jsonPath;
    int runs = 3;
    json out = json::array();
    std::vector<std::string> args(argv + 1, argv + argc);
    for (std::size_t i = 0; i < args.size(); ++i) {
      if (args[i] == "--json" && i + 1 < args.size()) {
        jsonPath = args[++i];
      } else if (args[i] == "--runs" && i + 1 < args.size()) {
        runs = std::max(1, std::stoi(args[++i]));
      } else if (args[i] == "--phantom" && i + 3 < args.size()) {
        const double spacing = std::stod(args[i + 1]);
        const int around = std::stoi(args[i + 2]), seed = std::stoi(args[i + 3]);
        i += 3;
        phantom::PhantomOptions o;
        o.seed = static_cast<std::uint32_t>(seed);
        o.meshStepMm = spacing;
        o.meshPointsAround = around;
        const phantom::ScanGeometry scan = phantom::MakeScan(phantom::MakeAnatomy(o), phantom::Posture::Supine, o);
        const auto segs = testing::PhantomTruthSegments(scan, o);
        const auto& t = segs[1];  // T
        out.push_back(Compare("phantom truth T " + args[i - 2] + " mm x " + args[i - 1] + " around", t.mesh, t.taenia[1], runs));
      } else if (i + 1 < args.size()) {
        const std::string dir = args[i], seg = args[++i];
        const std::string names = "ATDSR";
        const int id = static_cast<int>(names.find(seg));
        if (id < 0 || id >= 5) throw Error("segment letter expected, got " + seg);
        const TriangleMesh mesh = io::ReadMesh((fs::path(dir) / ("segment_" + seg + ".vtp")).string(), "segment");
        const PolylineSet taeniae = io::ReadPolylines((fs::path(dir) / "taeniae.vtp").string(), "taeniae");
        out.push_back(Compare(dir + " " + seg, mesh, CutPathFromTaeniae(taeniae, id), runs));
      } else {
        throw Error("usage: FlatteningVsCgal [--json OUT] [--runs N] [--phantom SPACING AROUND SEED] [DIR SEGMENT ...]");
      }
    }
    if (!jsonPath.empty()) std::ofstream(jsonPath) << out.dump(1) << "\n";
    return 0;
  } catch (const std::exception& e) {
    std::cerr << "FlatteningVsCgal: " << e.what() << "\n";
    return 1;
  }
}
