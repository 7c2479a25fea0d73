// ColonFlattening: landmarks folder -> conformal flat maps of the five segments, curvature
// images and a quality report (issue 6, DESIGN §2.3-2.4). Thin: arguments, reading, Libs/Flattening,
// writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "Flattening/BeltramiCoefficient.h"
#include "Flattening/ConformalFlattening.h"
#include "Flattening/MidpointSubdivision.h"
#include "Flattening/PrepareSegment.h"
#include "Flattening/SplitBoundaryChords.h"
#include "Flattening/CurvatureImagePng.h"
#include "Flattening/FlatTextures.h"
#include "Flattening/RasterizeFlatImage.h"
#include "Flattening/ShortestCutPath.h"
#include "Landmarks/ColonLandmarks.h"
#include "IO/ImageIO.h"
#include "IO/MeshIO.h"
#include "IO/SegmentFile.h"
#include "IO/StageReports.h"
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"

#include <nlohmann/json.hpp>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <optional>

namespace {

using namespace colonmap;
using namespace colonmap::flattening;
namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kNames[5] = {"A", "T", "D", "S", "R"};

// The cut path of segment `id` from taeniae.vtp (landmarks::CutTaeniaOf), checked against the
// segment mesh: each point must be the vertex its VertexId names.
std::optional<Eigen::VectorXi> CutPathOf(const PolylineSet& taeniae, int id, const TriangleMesh& mesh,
                                         const std::string& path, std::string* name) {
  std::optional<landmarks::CutTaenia> cut;
  try {
    cut = landmarks::CutTaeniaOf(taeniae, id);
  } catch (const Error& e) {
    throw InputError("taeniae", path, e.what());
  }
  if (!cut) return std::nullopt;
  for (Eigen::Index i = 0; i < cut->vertices.size(); ++i) {
    const int v = cut->vertices(i);
    if (v < 0 || v >= mesh.V.rows() || (mesh.V.row(v) - cut->points.row(i)).norm() > 1e-3)
      throw InputError("taeniae", path, "cut taenia of segment " + std::string(kNames[id]) + ": point " +
                       std::to_string(i) + " is not vertex " + std::to_string(v) + " of the segment mesh");
  }
  *name = cut->name;
  return cut->vertices;
}

json Times(const std::vector<std::pair<std::string, double>>& times) {
  json j;
  for (const auto& [step, s] : times) j[step] = s;
  return j;
}

void Run(cli::ModuleContext& ctx) {
  const std::string in = ctx.args.GetString("landmarksDirectory"), out = ctx.args.GetString("outputDirectory");
  if (in.empty()) throw Error("landmarks folder: no folder given");
  if (out.empty()) throw Error("output folder: no folder given");
  if (!fs::is_directory(in)) throw InputError("landmarks folder", in, fs::exists(in) ? "is not a folder" : "does not exist");
  FlatteningOptions options;
  options.width = ctx.args.GetString("widthMode") == "circumference" ? WidthMode::Circumference : WidthMode::Unit;
  options.cut = ctx.args.GetString("cutCondition") == "dirichlet" ? CutCondition::Dirichlet : CutCondition::Periodic;
  const double mmPerPixel = ctx.args.GetDouble("mmPerPixel");
  if (!(mmPerPixel > 0)) throw Error("mmPerPixel: must be positive");
  const bool textures = ctx.args.GetBool("textures"), reportTimes = ctx.args.GetBool("reportTimes");
  const long subdivisions = ctx.args.GetInt("subdivisions");
  if (subdivisions < 0 || subdivisions > 3) throw Error("subdivisions: must be 0, 1, 2 or 3");

  std::vector<int> present;
  std::vector<std::pair<std::string, double>> plan;
  json missing = json::array();
  for (int id = 0; id < 5; ++id) {
    const fs::path p = fs::path(in) / ("segment_" + std::string(kNames[id]) + ".vtp");
    if (fs::is_regular_file(p)) {
      present.push_back(id);
      plan.emplace_back(std::string("Segment ") + kNames[id], static_cast<double>(fs::file_size(p)) + 1.0);
    } else {
      missing.push_back(kNames[id]);
    }
  }
  if (present.empty()) throw InputError("landmarks folder", in, "holds none of segment_A.vtp ... segment_R.vtp");
  // ColonLandmarks always writes all five segments and taeniae.vtp: a folder without one of them
  // is not its output, and flattening the rest would register a colon with a gap (issue 24).
  if (!missing.empty())
    throw InputError("landmarks folder", in, "segment_" + missing[0].get<std::string>() +
                                                 ".vtp is missing (a ColonLandmarks folder holds all five segments)");
  if (!fs::is_regular_file(fs::path(in) / "taeniae.vtp"))
    throw InputError("landmarks folder", in, "taeniae.vtp is missing (ColonLandmarks writes it beside the segments)");
  // Checked at the door, before the long work: a bad landmarks.json is refused now, not after flattening.
  const io::LandmarksReport landmarksReport =
      io::ReadLandmarksReport((fs::path(in) / "landmarks.json").string(), "landmarks report");
  ctx.outputs.PrepareDirectory(out, "output folder");
  ctx.progress.Plan(plan);

  const fs::path taeniaePath = fs::path(in) / "taeniae.vtp";
  std::optional<PolylineSet> taeniae;
  taeniae = io::ReadPolylines(taeniaePath.string(), "taeniae");

  json report, segments;
  long flippedTotal = 0;
  double worstMu = 0.0;
  for (int id : present) {
    const std::string X = kNames[id];
    const std::string segPath = (fs::path(in) / ("segment_" + X + ".vtp")).string();
    ctx.progress.StartStage("Segment " + X, "flattening segment " + X);
    using Clock = std::chrono::steady_clock;
    Clock::time_point t0 = Clock::now();
    auto lap = [&t0]() {
      const Clock::time_point now = Clock::now();
      const double s = std::chrono::duration<double>(now - t0).count();
      t0 = now;
      return s;
    };
    TriangleMesh mesh = io::ReadMesh(segPath, "segment " + X);
    io::CheckSegmentId(mesh, id, "segment " + X, segPath);  // not renamed or swapped with another's file
    // Faces with all corners on an end loop would collapse under f1's fixed end values.
    const int chords = SplitBoundaryChords(mesh);
    if (chords)
      ctx.progress.Note("ColonFlattening: segment " + X + ": " + std::to_string(chords) +
                        " edges joining two end-loop vertices split at their midpoint");
    const double readSeconds = lap();
    ctx.progress.Report(0.1);
    Eigen::VectorXd arc;
    if (auto a = mesh.pointData.find("CenterlineArcLength"); a != mesh.pointData.end()) arc = a->second.values.col(0);
    else ctx.progress.Note("ColonFlattening: WARNING: segment " + X + " has no CenterlineArcLength: v runs from the cut's last to its first loop");
    std::string cutName = "shortest-path";
    std::optional<Eigen::VectorXi> path;
    if (taeniae) path = CutPathOf(*taeniae, id, mesh, taeniaePath.string(), &cutName);
    FlatteningResult r;
    int keptSplit = 0, negativeLeft = 0;
    try {
      if (!path) {
        ctx.progress.Note("ColonFlattening: WARNING: segment " + X + " has no cut taenia (IsCut = 1): cutting along a shortest edge path");
        const std::vector<std::vector<int>> loops = surface::BoundaryLoops(mesh.F);
        if (loops.size() != 2) throw Error("not a topological cylinder: " + std::to_string(loops.size()) + " boundary loops");
        path = ShortestCutPath(mesh.V, mesh.F, loops[0], loops[1]);
      }
      // Finer faces on the same surface (MidpointSubdivision.h): |mu| halves per level.
      if (subdivisions > 0) {
        // Curvature of the surface as given, interpolated to the new vertices (computed on the
        // finer faces it would be zero inside the old faces and a crease on their edges).
        if (!mesh.pointData.count("MeanCurvature"))
          mesh.pointData["MeanCurvature"] = DataArray{surface::MeanCurvature(mesh.V, mesh.F), false};
        MidpointSubdivision(mesh, &*path, static_cast<int>(subdivisions));
        if (auto a = mesh.pointData.find("CenterlineArcLength"); a != mesh.pointData.end()) arc = a->second.values.col(0);
      }
      // Kept edges (the cut, a few next to the loops) that would keep a negative weight in the
      // intrinsic Delaunay triangulation are split at their midpoints (PrepareSegment.h).
      if (options.laplacian == LaplacianMode::IntrinsicDelaunay) {
        keptSplit = SplitNonDelaunayKeptEdges(mesh, *path, 4, &negativeLeft);
        if (auto a = mesh.pointData.find("CenterlineArcLength"); a != mesh.pointData.end()) arc = a->second.values.col(0);
      }
      SubProgress sub(ctx.progress, 0.1, 0.8);
      r = ConformalFlattening(mesh.V, mesh.F, *path, arc, options, sub);
    } catch (const Cancelled&) {
      throw;
    } catch (const Error& e) {
      throw InputError("segment " + X, segPath, e.what());
    }
    std::vector<std::pair<std::string, double>> times = {{"read", readSeconds}};
    times.insert(times.end(), r.times.begin(), r.times.end());
    lap();

    // Quality of the map, on the faces it is drawn on (with the intrinsic Delaunay Laplacian
    // those faces; ConformalFlattening.h).
    const Eigen::VectorXcd mu = BeltramiCoefficient(r.cut.V, r.uv, r.cut.F);
    const DistortionStats q = SummarizeDistortion(r.cut.V, r.uv, r.cut.F, mu);
    times.emplace_back("quality", lap());

    // Per-vertex arrays of the cut mesh: the input's, copied to both copies of the cut.
    TriangleMesh flat, surface3d;
    surface3d.V = r.cut.V;
    surface3d.F = r.cut.F;
    for (const auto& [name, array] : mesh.pointData) {
      DataArray a{Eigen::MatrixXd(r.cut.V.rows(), array.values.cols()), array.integer};
      for (Eigen::Index i = 0; i < r.cut.V.rows(); ++i) a.values.row(i) = array.values.row(r.cut.original(i));
      surface3d.pointData[name] = a;
    }
    if (!surface3d.pointData.count("MeanCurvature")) {
      const Eigen::VectorXd H = surface::MeanCurvature(mesh.V, mesh.F);
      Eigen::VectorXd Hc(r.cut.V.rows());
      for (Eigen::Index i = 0; i < Hc.size(); ++i) Hc(i) = H(r.cut.original(i));
      surface3d.pointData["MeanCurvature"] = DataArray{Hc, false};
    }
    surface3d.pointData["FlatUV"] = DataArray{r.uv, false};
    Eigen::VectorXd absMu = mu.cwiseAbs(), argMu(mu.size());
    for (Eigen::Index f = 0; f < mu.size(); ++f) argMu(f) = std::arg(mu(f));
    surface3d.cellData["BeltramiAbs"] = DataArray{absMu, false};
    surface3d.cellData["BeltramiArg"] = DataArray{argMu, false};
    if (textures) {
      Eigen::VectorXd checker, circles;
      FlatTextures(r.uv, r.cut.F, r.scale, 8, checker, circles);
      surface3d.cellData["Checkerboard"] = DataArray{checker, true};
      surface3d.cellData["Circles"] = DataArray{circles, true};
    }
    flat = surface3d;
    flat.V = Eigen::MatrixXd::Zero(r.cut.V.rows(), 3);
    flat.V.leftCols(2) = r.uv;
    flat.pointData["Position3D"] = DataArray{r.cut.V, false};

    // Curvature image over the rectangle in mm (periodic across the cut).
    const double toMm = r.circumferenceMm / r.scale;
    const int nx = std::max(1, static_cast<int>(std::lround(r.circumferenceMm / mmPerPixel)));
    const int ny = std::max(1, static_cast<int>(std::lround(r.lengthMm / mmPerPixel)));
    RasterInfo ri;
    const Volume<float> image =
        RasterizeFlatImage(r.uv * toMm, r.cut.F, surface3d.pointData.at("MeanCurvature").values.col(0), r.circumferenceMm,
                           r.lengthMm, nx, ny, &ri, options.cut == CutCondition::Periodic ? r.circumferenceMm : 0.0);
    double low = 0, high = 0;
    const std::vector<std::uint8_t> png = CurvatureImagePng(image, ColourImageOptions{}, &low, &high);
    times.emplace_back("images", lap());
    ctx.progress.Report(0.95);

    auto stage = [&](const std::string& name) { return ctx.outputs.Stage((fs::path(out) / name).string(), "output " + name); };
    io::WriteMesh(flat, stage("flat_" + X + ".vtp"), "flat mesh " + X);
    io::WriteMesh(surface3d, stage("surface_" + X + ".vtp"), "cut surface " + X);
    io::WriteImage(image, stage("curvature_" + X + ".nrrd"), "curvature image " + X);
    // The same image as a volume for the scene (one image parameter per segment), when asked for.
    if (const std::string node = ctx.args.GetString("curvatureImage" + X); !node.empty())
      io::WriteImage(image, ctx.outputs.Stage(node, "curvature volume " + X), "curvature volume " + X);
    {
      const std::string p = stage("curvature_" + X + ".png");
      std::ofstream f(p, std::ios::binary);
      f.write(reinterpret_cast<const char*>(png.data()), static_cast<std::streamsize>(png.size()));
      if (!f) throw InputError("output picture", p, "cannot be written");
    }
    times.emplace_back("write", lap());
    ctx.progress.EndStage();

    json s;
    s["vertices"] = mesh.V.rows();
    s["cutVertices"] = r.cut.V.rows();
    s["faces"] = mesh.F.rows();
    s["cut"] = cutName;
    s["cutPathVertices"] = path->size();
    s["flippedTriangles"] = q.flipped;
    s["preparation"] = {{"subdivisions", subdivisions}, {"boundaryChordsSplit", chords}, {"keptEdgesSplit", keptSplit},
                        {"negativeWeightsLeft", negativeLeft}, {"facesChanged", r.changedFaces},
                        {"edgeGapBoundMm", r.edgeGapBound}, {"nonPositiveFlux", r.nonPositiveFlux}};
    s["beltramiAbs"] = {{"mean", q.muMean}, {"p99", q.muP99}, {"max", q.muMax}};
    s["areaRatio"] = {{"min", q.areaRatioMin}, {"p01", q.areaRatioP01}, {"median", q.areaRatioMedian},
                      {"p99", q.areaRatioP99}, {"max", q.areaRatioMax}, {"logStd", q.logAreaRatioStd}};
    s["lambda"] = r.lambda;
    s["widthMm"] = r.circumferenceMm;
    s["lengthMm"] = r.lengthMm;
    s["flatWidth"] = r.scale;
    s["flatLength"] = r.scale / std::fabs(r.lambda);
    s["image"] = {{"size", {nx, ny}}, {"mmPerPixel", {r.circumferenceMm / nx, r.lengthMm / ny}},
                  {"coveredPixels", ri.covered}, {"filledPixels", ri.filled}, {"colourRange", {low, high}}};
    if (reportTimes) s["times"] = Times(times);
    segments[X] = s;
    flippedTotal += q.flipped;
    worstMu = std::max(worstMu, q.muMean);

    std::string steps;
    for (const auto& [step, sec] : times) steps += (steps.empty() ? "" : ", ") + step + " " + cli::FormatNumber(sec) + " s";
    ctx.progress.Note("ColonFlattening: segment " + X + ": " + std::to_string(mesh.F.rows()) + " faces, cut " + cutName +
                      ", lambda " + cli::FormatNumber(r.lambda) + ", " + cli::FormatNumber(r.circumferenceMm) + " x " +
                      cli::FormatNumber(r.lengthMm) + " mm, flipped " + std::to_string(q.flipped) + ", |mu| mean " +
                      cli::FormatNumber(q.muMean) + " p99 " + cli::FormatNumber(q.muP99) + " max " +
                      cli::FormatNumber(q.muMax) + "; times: " + steps);
    if (q.flipped > 0)
      ctx.progress.Note("ColonFlattening: WARNING: segment " + X + ": " + std::to_string(q.flipped) +
                        " flipped triangles in the flat map");
  }
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m.get<std::string>();
    ctx.progress.Note("ColonFlattening: WARNING: missing segments skipped: " + list);
  }
  report["segments"] = segments;
  report["missingSegments"] = missing;
  report["widthMode"] = options.width == WidthMode::Circumference ? "circumference" : "unit";
  report["cutCondition"] = options.cut == CutCondition::Periodic ? "periodic" : "dirichlet";
  report["laplacian"] = options.laplacian == LaplacianMode::IntrinsicDelaunay ? "intrinsicDelaunay" : "mesh";
  report["mmPerPixel"] = mmPerPixel;
  report["subdivisions"] = subdivisions;
  report["flippedTriangles"] = flippedTotal;
  // The landmarks' joint flexure choice, handed on: the registration must know when the segments
  // are the alignment's guess rather than both scans' anatomy (issue 20).
  if (const auto& j = landmarksReport.jointChoice)
    report["jointChoice"] = {{"pairedWith", j->pairedWith}, {"consistent", j->consistent}, {"fallback", j->fallback}};
  {
    const std::string p = ctx.outputs.Stage((fs::path(out) / "flattening.json").string(), "output flattening.json");
    std::ofstream f(p);
    f << report.dump(2) << "\n";
    if (!f) throw InputError("output report", p, "cannot be written");
  }
  ctx.SetReturn("segments", std::to_string(present.size()));
  ctx.SetReturn("flippedTriangles", std::to_string(flippedTotal));
  ctx.SetReturn("worstMeanBeltrami", cli::FormatNumber(worstMu));
}

}  // namespace

COLONMAP_MODULE_BODY(ColonFlattening, Run)
