// ColonFlatViews: flattened and distortion views of a registration (issue 8, DESIGN §2.4-2.5,
// paper Figs. 9, 12, 13). Thin: arguments, reading the flattening and registration folders,
// Libs/Views for the pictures and measures, writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"
#include "IO/MeshIO.h"
#include "IO/StageReports.h"
#include "Registration/FlatLocator.h"
#include "Registration/FoldFeatures.h"
#include "Views/ColourMap.h"
#include "Views/DistortionStatistics.h"
#include "Views/DistortionTextures.h"
#include "Views/FlatComposition.h"
#include "Views/FlatImageCorrelation.h"
#include "Views/FlatResampling.h"
#include "Views/FlatSegmentMesh.h"
#include "Views/EndoluminalRenderer.h"  // RenderDisplayAvailable
#include "Views/MorphSequence.h"
#include "Views/SurfaceCamera.h"
#include "Views/SurfaceRenderer.h"
#include "Views/SurfaceScene.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <array>

namespace colonmap::modules {
namespace {

using namespace colonmap::views;
namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kNames[5] = {"A", "T", "D", "S", "R"};
constexpr double kPi = 3.14159265358979323846;
const Bgr kGrey{150, 150, 150};
const Bgr kOutside{230, 230, 230};

// One scan's side of one segment: its part of the registration mesh and its flat picture grid.
struct Side {
  FlatSegmentMesh mesh;
  Eigen::MatrixXd uv;       // own flat coordinates
  Eigen::MatrixXd otherUV;  // the registration's image of each vertex in the other scan's flat coordinates
  double period = 0.0, height = 0.0, toMm = 0.0;
  Volume<float> curvature;
  FlatGrid grid;
  FlatPixelHits hits;
};

double PeriodOf(const io::FlatteningReport& report, const std::string& X, const Eigen::MatrixXd& uv, const Eigen::MatrixXd& position,
                const fs::path& flatDir, const std::string& scan) {
  std::optional<double> reported;
  if (const auto it = report.segments.find(X); it != report.segments.end()) reported = it->second.flatWidth;
  return registration::CheckedFlatPeriod(reported, uv, position, X, scan + " flattening report",
                                         (flatDir / "flattening.json").string());
}

Side MakeSide(const TriangleMesh& whole, const std::string& wholePath, int id, const std::string& ownUV, const std::string& otherUV,
              const fs::path& flatDir, const io::FlatteningReport& report, double ppu, const std::string& scan, ProgressSink& progress) {
  const std::string X = kNames[id];
  Side s;
  s.mesh = ExtractSegment(whole, id, scan + " registration mesh '" + wholePath + "'");
  if (s.mesh.F.rows() == 0) throw InputError(scan + " registration mesh", wholePath, "segment " + X + " has no faces");
  s.uv = s.mesh.PointRows(PointArray(whole, ownUV, 2, scan + " registration mesh '" + wholePath + "'"));
  s.otherUV = s.mesh.PointRows(PointArray(whole, otherUV, 2, scan + " registration mesh '" + wholePath + "'"));
  s.period = PeriodOf(report, X, s.uv, s.mesh.PointRows(whole.V), flatDir, scan);
  if (!(s.period > 0)) throw InputError(scan + " flattening folder", flatDir.string(), "the flat width of segment " + X + " is unknown");
  s.height = s.uv.col(1).maxCoeff();
  if (!(s.height > 0)) throw InputError(scan + " registration mesh", wholePath, "segment " + X + " has no flat length");
  const fs::path image = flatDir / ("curvature_" + X + ".nrrd");
  if (!fs::exists(image)) throw InputError(scan + " curvature image " + X, image.string(), "does not exist");
  s.curvature = io::ReadImage<float>(image.string(), scan + " curvature image " + X);
  if (s.curvature.size[2] != 1 || s.curvature.size[0] < 1)
    throw InputError(scan + " curvature image " + X, image.string(), "is not a 2D flat image");
  s.toMm = static_cast<double>(s.curvature.size[0]) * s.curvature.spacing.x() / s.period;
  s.grid = GridFor(s.period, s.height, ppu);
  // Pixels within 1.5 pixels of the mesh count as inside (rounding at the rectangle's rim).
  s.hits = LocatePixels(s.uv, s.mesh.F, s.period, s.grid, 1.5 / ppu, progress);
  return s;
}

Eigen::VectorXf ToFloat(const Eigen::VectorXd& v) { return v.cast<float>(); }

// Folds of one side (Registration/FoldFeatures, the detector ColonRegistration --method harmonic
// uses) from the registration mesh's MeanCurvature.
std::vector<registration::FoldFeature> Folds(const Side& s, const TriangleMesh& whole) {
  const auto h = whole.pointData.find("MeanCurvature");
  if (h == whole.pointData.end() || h->second.values.cols() != 1) return {};
  registration::FlatSegment flat;
  flat.uv = s.uv;
  flat.F = s.mesh.F;
  flat.position = s.mesh.PointRows(whole.V);
  flat.period = s.period;
  return registration::DetectFolds(flat, s.mesh.PointRows(h->second.values).col(0));
}

Eigen::Vector2d ToPixel(const Side& s, const Eigen::Vector2d& uv) {
  return {uv.x() / s.grid.width * s.grid.nx, s.grid.ny - uv.y() / s.grid.height * s.grid.ny};
}

// Index of the fold whose centroid is `uv` (as registration.json lists it), -1 when none is.
int FoldAt(const std::vector<registration::FoldFeature>& folds, const Eigen::Vector2d& uv, double period) {
  for (std::size_t k = 0; k < folds.size(); ++k) {
    double du = folds[k].centroid.x() - uv.x();
    du -= period * std::round(du / period);
    if (std::hypot(du, folds[k].centroid.y() - uv.y()) < 1e-6 * period) return static_cast<int>(k);
  }
  return -1;
}

void DrawFold(ColourImage& picture, const Side& s, const registration::FoldFeature& f, const Bgr& colour, const std::string& label) {
  DrawFeature(picture, ToPixel(s, f.centroid), ToPixel(s, f.ends[0]), ToPixel(s, f.ends[1]), colour, label);
}

json Summary(const DilatationSummary& d) { return {{"mean", d.mean}, {"p99", d.p99}, {"max", d.max}, {"faces", d.faces}, {"infinite", d.infinite}}; }

void WriteBytes(const std::vector<std::uint8_t>& bytes, const std::string& path) {
  std::ofstream f(path, std::ios::binary);
  f.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
  if (!f) throw InputError("output picture", path, "cannot be written");
}

// A rendered view under a title line (no label margin).
ColourImage Titled(const ColourImage& picture, const std::string& title) { return StackColumn({picture}, {""}, title, 0, 0); }

// Per vertex of `mesh`: the flat width of its segment (0 where the segment was not drawn).
Eigen::VectorXd SegmentWidths(const TriangleMesh& mesh, const std::array<double, 5>& width) {
  const auto& id = mesh.pointData.at("SegmentId").values;
  Eigen::VectorXd w(mesh.V.rows());
  for (Eigen::Index i = 0; i < w.size(); ++i) {
    const long k = std::lround(id(i, 0));
    w(i) = k >= 0 && k < 5 ? width[static_cast<std::size_t>(k)] : 0.0;
  }
  return w;
}

// The faces of `mesh` whose three corners lie in drawn segments (width > 0), and the flat
// coordinates there (texture scenes need a width everywhere).
TriangleMesh DrawnPart(const TriangleMesh& mesh, const Eigen::VectorXd& width) {
  TriangleMesh out;
  out.V = mesh.V;
  std::vector<Eigen::Index> keep;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    if (width(mesh.F(f, 0)) > 0 && width(mesh.F(f, 1)) > 0 && width(mesh.F(f, 2)) > 0) keep.push_back(f);
  out.F.resize(static_cast<Eigen::Index>(keep.size()), 3);
  for (std::size_t k = 0; k < keep.size(); ++k) out.F.row(static_cast<Eigen::Index>(k)) = mesh.F.row(keep[k]);
  return out;
}

}  // namespace

void RunColonFlatViews(cli::ModuleContext& ctx) {
  const std::string sdir = ctx.args.GetString("supineFlatteningDirectory"), pdir = ctx.args.GetString("proneFlatteningDirectory"),
                    rdir = ctx.args.GetString("registrationDirectory"), out = ctx.args.GetString("outputDirectory");
  if (sdir.empty() || pdir.empty() || rdir.empty()) throw Error("input folders: the supine and prone flattening folders and the registration folder are needed");
  if (out.empty()) throw Error("output folder: no folder given");
  for (const auto& [dir, what] : {std::pair{sdir, "supine flattening folder"}, std::pair{pdir, "prone flattening folder"},
                                  std::pair{rdir, "registration folder"}})
    if (!fs::is_directory(dir)) throw InputError(what, dir, fs::exists(dir) ? "is not a folder" : "does not exist");
  const long frames = ctx.args.GetInt("morphFrames");
  const double ppu = ctx.args.GetDouble("pixelsPerUnit");
  if (frames < 2 || frames > 200) throw Error("morphFrames: must be between 2 and 200");
  if (!(ppu >= 8 && ppu <= 1024)) throw Error("pixelsPerUnit: must be between 8 and 1024");
  const SurfaceViewDirection view3D = SurfaceViewNamed(ctx.args.Has("view3D") ? ctx.args.GetString("view3D") : std::string("anterior"));
  // 3D pictures need an X display (VTK renders through GLX here). Slicer always has one; a batch
  // run without one still gets every other output, and a note and flatviews.json say why not.
  std::string skip3DReason;
  if (ctx.args.GetBool("skip3D")) skip3DReason = "skipped on request (--skip3D)";
  else if (std::string why; !RenderDisplayAvailable(&why)) skip3DReason = why + "; run under xvfb-run -a for the 3D pictures";
  const fs::path regPath = fs::path(rdir) / "registration.vtp", pronePath = fs::path(rdir) / "registration_prone.vtp";
  for (const fs::path& p : {regPath, pronePath})
    if (!fs::is_regular_file(p)) throw InputError("registration", p.string(), "does not exist");

  ctx.progress.Plan({{"Read", 1.0}, {"Segments", 4.0}, {"Pictures", 1.0}, {"Write", 2.0}, {"Render3D", skip3DReason.empty() ? 3.0 : 0.1}});
  ctx.progress.StartStage("Read", "reading the registration");
  const TriangleMesh supine = io::ReadMesh(regPath.string(), "registration");
  ctx.progress.Report(0.5);
  const TriangleMesh prone = io::ReadMesh(pronePath.string(), "prone registration mesh");
  const std::string regWhat = "registration '" + regPath.string() + "'";
  const Eigen::MatrixXd& pronePosition = PointArray(supine, "PronePosition", 3, regWhat);
  const Eigen::MatrixXd& K = CellArray(supine, "Dilatation", 1, regWhat);
  const Eigen::MatrixXd& muArg = CellArray(supine, "BeltramiArg", 1, regWhat);
  const Eigen::MatrixXd& segmentId = PointArray(supine, "SegmentId", 1, regWhat);
  const io::RegistrationReport regReport =
      io::ReadRegistrationReport((fs::path(rdir) / "registration.json").string(), "registration report");
  const io::FlatteningReport sReport = io::ReadFlatteningReport((fs::path(sdir) / "flattening.json").string(), "supine flattening report");
  const io::FlatteningReport pReport = io::ReadFlatteningReport((fs::path(pdir) / "flattening.json").string(), "prone flattening report");
  std::vector<int> present;
  for (int id = 0; id < 5; ++id)
    if ((segmentId.col(0).array().round() == id).any()) present.push_back(id);
  if (present.empty()) throw InputError("registration", regPath.string(), "has no vertices with SegmentId 0..4");
  ctx.outputs.PrepareDirectory(out, "output folder");
  ctx.progress.EndStage();

  // Per segment: the pictures (as value matrices) and the measures.
  ctx.progress.StartStage("Segments", "resampling the flat pictures through the registration");
  struct SegmentViews {
    std::string name;
    Eigen::MatrixXf supineH, proneH, registeredH, K, theta, checkerS, checkerP, circlesS, circlesP;
    Side s, p;
    std::vector<registration::FoldFeature> sFolds, pFolds;
  };
  std::vector<SegmentViews> views;
  json segments;
  Eigen::VectorXf allSupine, allRegistered, allUnregistered;  // pooled correlation
  const TextureOptions textures;
  for (std::size_t k = 0; k < present.size(); ++k) {
    const int id = present[k];
    const std::string X = kNames[id];
    SubProgress sub(ctx.progress, static_cast<double>(k) / present.size(), (k + 0.5) / present.size());
    SegmentViews v;
    v.name = X;
    v.s = MakeSide(supine, regPath.string(), id, "SupineFlatUV", "ProneFlatUV", sdir, sReport, ppu, "supine", sub);
    SubProgress sub2(ctx.progress, (k + 0.5) / present.size(), (k + 0.9) / present.size());
    v.p = MakeSide(prone, pronePath.string(), id, "ProneFlatUV", "SupineFlatUV", pdir, pReport, ppu, "prone", sub2);
    const Side& s = v.s;
    const Side& p = v.p;
    // Curvature: supine and prone in their own coordinates; prone resampled at the supine
    // pixels through the registration; prone at the same (u, v) without registration.
    const Eigen::MatrixXd sOwn = MapPixels(s.hits, s.mesh.F, s.uv, s.period);
    const Eigen::VectorXf hS = SampleFlatImage(s.curvature, sOwn, s.toMm, true);
    const Eigen::VectorXf hP = SampleFlatImage(p.curvature, MapPixels(p.hits, p.mesh.F, p.uv, p.period), p.toMm, true);
    const Eigen::VectorXf hR = SampleFlatImage(p.curvature, MapPixels(s.hits, s.mesh.F, s.otherUV, p.period), p.toMm, true);
    const Eigen::VectorXf hU = SampleFlatImage(p.curvature, sOwn, p.toMm, true);
    const Correlation cR = FlatImageCorrelation(hS, hR), cU = FlatImageCorrelation(hS, hU);
    for (auto [all, add] : {std::pair{&allSupine, &hS}, std::pair{&allRegistered, &hR}, std::pair{&allUnregistered, &hU}}) {
      Eigen::VectorXf joined(all->size() + add->size());
      joined << *all, *add;
      *all = joined;
    }
    v.supineH = PixelsToPicture(hS, s.grid);
    v.proneH = PixelsToPicture(hP, p.grid);
    v.registeredH = PixelsToPicture(hR, s.grid);
    // Distortion of the registration on the supine flat domain.
    const Eigen::VectorXd segK = s.mesh.FaceRows(K).col(0), segTheta = DistortionAngle(s.mesh.FaceRows(muArg).col(0));
    v.K = PixelsToPicture(ToFloat(FaceValuesAtPixels(s.hits, segK)), s.grid);
    v.theta = PixelsToPicture(ToFloat(FaceValuesAtPixels(s.hits, segTheta)), s.grid);
    // Textures on the supine domain, and carried to the prone domain (each prone pixel shows
    // the texture at its supine image).
    const Eigen::MatrixXd pToS = MapPixels(p.hits, p.mesh.F, p.otherUV, s.period);
    v.checkerS = PixelsToPicture(ToFloat(CheckerboardAt(sOwn, s.period, textures)), s.grid);
    v.checkerP = PixelsToPicture(ToFloat(CheckerboardAt(pToS, s.period, textures)), p.grid);
    v.circlesS = PixelsToPicture(ToFloat(CirclesAt(sOwn, s.period, textures)), s.grid);
    v.circlesP = PixelsToPicture(ToFloat(CirclesAt(pToS, s.period, textures)), p.grid);
    v.sFolds = Folds(s, supine);
    v.pFolds = Folds(p, prone);
    const DilatationSummary d = SummarizeDilatation(segK);

    json j;
    j["supinePicture"] = {s.grid.nx, s.grid.ny};
    j["pronePicture"] = {p.grid.nx, p.grid.ny};
    j["supineFlatSize"] = {s.period, s.height};
    j["proneFlatSize"] = {p.period, p.height};
    j["supineFaces"] = s.mesh.F.rows();
    j["proneFaces"] = p.mesh.F.rows();
    j["dilatation"] = Summary(d);
    j["curvatureCorrelation"] = {{"unregistered", cU.r}, {"registered", cR.r}, {"unregisteredPixels", cU.pixels},
                                 {"registeredPixels", cR.pixels}};
    segments[X] = j;
    views.push_back(std::move(v));
    ctx.progress.Report((k + 1.0) / present.size());
  }
  ctx.progress.EndStage();

  // Pictures.
  ctx.progress.StartStage("Pictures", "drawing the flat views");
  std::vector<const Eigen::MatrixXf*> hAll;
  for (const SegmentViews& v : views) {
    hAll.push_back(&v.supineH);
    hAll.push_back(&v.proneH);
  }
  const std::array<double, 2> hRange = QuantileRange(hAll, 0.01, 0.99);
  const DilatationSummary dAll = SummarizeDilatation(K.col(0));
  const double kHigh = std::max(dAll.p99, 1.0 + 1e-3);
  std::vector<std::string> labels;
  for (const SegmentViews& v : views) labels.push_back(v.name);
  // Progress per segment picture drawn (10 columns of segment pictures in all).
  const double totalSteps = 10.0 * views.size();
  double steps = 0;
  auto step = [&]() { ctx.progress.Report(++steps / totalSteps); };
  auto column = [&](auto picture, const std::string& title) {
    std::vector<ColourImage> pics;
    for (const SegmentViews& v : views) {
      pics.push_back(picture(v));
      step();
    }
    return StackColumn(pics, labels, title);
  };
  auto curvature = [&](const Eigen::MatrixXf& m) { return ColourMapValues(m, hRange[0], hRange[1], ColourMapKind::Turbo, kOutside); };
  auto bar = [&](int height, double low, double high, ColourMapKind kind, const std::string& title, const std::string& format) {
    return ColourBar(std::min(height, 400), low, high, kind, title, 5, format);
  };
  std::map<std::string, ColourImage> pictures;
  {
    const ColourImage a = column([&](const SegmentViews& v) { return curvature(v.supineH); }, "supine");
    const ColourImage b = column([&](const SegmentViews& v) { return curvature(v.proneH); }, "prone");
    pictures["flat_pair_unregistered.png"] = WithCaption(
        SideBySide({a, b, bar(a.height, hRange[0], hRange[1], ColourMapKind::Turbo, "H (1/mm)", "%.3f")}),
        "Mean curvature, each scan in its own flat coordinates (u around, v from the anal end up)");
    const ColourImage c = column([&](const SegmentViews& v) { return curvature(v.registeredH); }, "prone, registered");
    pictures["flat_pair_registered.png"] = WithCaption(
        SideBySide({a, c, bar(a.height, hRange[0], hRange[1], ColourMapKind::Turbo, "H (1/mm)", "%.3f")}),
        "Mean curvature; prone resampled into supine (u, v) through the registration: same place, same anatomy");
  }
  long matchedTotal = 0, foundTotal = 0, sFoldsTotal = 0, pFoldsTotal = 0;
  {
    std::vector<ColourImage> sp, pp;
    for (SegmentViews& v : views) {
      ColourImage a = curvature(v.supineH), b = curvature(v.proneH);
      std::vector<bool> sMatched(v.sFolds.size(), false), pMatched(v.pFolds.size(), false);
      const auto listed = regReport.matches.find(v.name);
      const std::vector<io::FoldMatch> none;
      struct Pair { int s, p; std::string label; };
      std::vector<Pair> pairs;
      for (const io::FoldMatch& m : listed == regReport.matches.end() ? none : listed->second) {
        const Eigen::Vector2d& su = m.supineUV;
        const Eigen::Vector2d& pu = m.proneUV;
        const int fs = FoldAt(v.sFolds, su, v.s.period), fp = FoldAt(v.pFolds, pu, v.p.period);
        if (fs >= 0) sMatched[fs] = true;
        if (fp >= 0) pMatched[fp] = true;
        pairs.push_back({fs, fp, m.label});
        // A match whose fold the detector here does not reproduce is drawn at its listed centroid.
        if (fs < 0) DrawFeature(a, ToPixel(v.s, su), ToPixel(v.s, su), ToPixel(v.s, su), MatchColour(static_cast<int>(matchedTotal + pairs.size() - 1)), pairs.back().label);
        if (fp < 0) DrawFeature(b, ToPixel(v.p, pu), ToPixel(v.p, pu), ToPixel(v.p, pu), MatchColour(static_cast<int>(matchedTotal + pairs.size() - 1)), pairs.back().label);
      }
      // Unmatched first (grey, underneath), then the matched pairs in their colours.
      for (std::size_t f = 0; f < v.sFolds.size(); ++f) if (!sMatched[f]) DrawFold(a, v.s, v.sFolds[f], kGrey, "");
      for (std::size_t f = 0; f < v.pFolds.size(); ++f) if (!pMatched[f]) DrawFold(b, v.p, v.pFolds[f], kGrey, "");
      for (std::size_t m = 0; m < pairs.size(); ++m) {
        const Bgr c = MatchColour(static_cast<int>(matchedTotal + m));
        if (pairs[m].s >= 0) DrawFold(a, v.s, v.sFolds[pairs[m].s], c, pairs[m].label);
        if (pairs[m].p >= 0) DrawFold(b, v.p, v.pFolds[pairs[m].p], c, pairs[m].label);
      }
      long found = 0;  // matched folds the detector here reproduces (both sides count)
      for (const Pair& m : pairs) found += (m.s >= 0) + (m.p >= 0);
      foundTotal += found;
      segments[v.name]["features"] = {{"supine", v.sFolds.size()}, {"prone", v.pFolds.size()}, {"matched", pairs.size()}, {"found", found}};
      matchedTotal += static_cast<long>(pairs.size());
      sFoldsTotal += static_cast<long>(v.sFolds.size());
      pFoldsTotal += static_cast<long>(v.pFolds.size());
      sp.push_back(a);
      pp.push_back(b);
      step();
    }
    const ColourImage a = StackColumn(sp, labels, "supine folds"), b = StackColumn(pp, labels, "prone folds");
    char caption[160];
    std::snprintf(caption, sizeof caption, "Fold features: %ld matched pairs in matching colours; unmatched grey (%ld supine, %ld prone folds)",
                  matchedTotal, sFoldsTotal, pFoldsTotal);
    pictures["features_matched.png"] = WithCaption(SideBySide({a, b, bar(a.height, hRange[0], hRange[1], ColourMapKind::Turbo, "H (1/mm)", "%.3f")}), caption);
  }
  {
    const ColourImage a = column([&](const SegmentViews& v) { return ColourMapValues(v.K, 1.0, kHigh, ColourMapKind::Turbo, kOutside); }, "K");
    pictures["dilatation_flat.png"] = WithCaption(SideBySide({a, bar(a.height, 1.0, kHigh, ColourMapKind::Turbo, "K", "%.3f")}),
                                                  "Dilatation K = (1+|mu|)/(1-|mu|) on the supine flat domain");
    const ColourImage b = column([&](const SegmentViews& v) { return ColourMapValues(v.theta, -kPi / 2, kPi / 2, ColourMapKind::Hsv, kOutside); }, "theta");
    pictures["angle_flat.png"] = WithCaption(SideBySide({b, bar(b.height, -90.0, 90.0, ColourMapKind::Hsv, "deg", "%.0f")}),
                                             "Angle theta = arg(mu)/2 on the supine flat domain");
    auto grey = [&](const Eigen::MatrixXf& m) { return ColourMapValues(m, 0.0, 1.0, ColourMapKind::Grey, {200, 170, 140}); };
    pictures["checkerboard_pair.png"] = WithCaption(
        SideBySide({column([&](const SegmentViews& v) { return grey(v.checkerS); }, "supine"),
                    column([&](const SegmentViews& v) { return grey(v.checkerP); }, "carried to prone")}),
        "Checkerboard on the supine flat domain and carried to the prone one");
    pictures["circles_pair.png"] = WithCaption(
        SideBySide({column([&](const SegmentViews& v) { return grey(v.circlesS); }, "supine"),
                    column([&](const SegmentViews& v) { return grey(v.circlesP); }, "carried to prone")}),
        "Circles on the supine flat domain and carried to the prone one");
  }
  ctx.progress.EndStage();

  // Writing: pictures, distortion.vtp, morph frames, report.
  ctx.progress.StartStage("Write", "writing the views");
  json files = json::array();
  auto stage = [&](const std::string& name) {
    files.push_back(name);
    return ctx.outputs.Stage((fs::path(out) / name).string(), "output " + name);
  };
  double written = 0;
  for (const auto& [name, picture] : pictures) {
    WriteBytes(EncodePng(picture), stage(name));
    segments["_pictures"][name] = {picture.width, picture.height};
    ctx.progress.Report(0.3 * ++written / pictures.size());
  }
  ctx.progress.Report(0.3);
  {
    TriangleMesh d;
    d.V = supine.V;
    d.F = supine.F;
    for (const char* name : {"SegmentId", "SupineFlatUV", "ProneFlatUV", "PronePosition"})
      if (auto it = supine.pointData.find(name); it != supine.pointData.end()) d.pointData[name] = it->second;
    for (const char* name : {"BeltramiAbs", "BeltramiArg", "Dilatation"})
      if (auto it = supine.cellData.find(name); it != supine.cellData.end()) d.cellData[name] = it->second;
    d.cellData["Angle"] = DataArray{DistortionAngle(muArg.col(0)), false};
    d.pointData["ProneDisplacement"] = DataArray{pronePosition - supine.V, false};
    // Textures per vertex on each segment's supine flat coordinates (the same values sit at
    // PronePosition on the prone surface).
    Eigen::VectorXd checker = Eigen::VectorXd::Zero(supine.V.rows()), circles = checker;
    for (const SegmentViews& v : views) {
      const Eigen::VectorXd c = CheckerboardAt(v.s.uv, v.s.period, textures), o = CirclesAt(v.s.uv, v.s.period, textures);
      for (Eigen::Index i = 0; i < v.s.mesh.vertices.size(); ++i) {
        checker(v.s.mesh.vertices(i)) = c(i);
        circles(v.s.mesh.vertices(i)) = o(i);
      }
    }
    d.pointData["Checkerboard"] = DataArray{checker, true};
    d.pointData["Circles"] = DataArray{circles, true};
    io::WriteMesh(d, stage("distortion.vtp"), "distortion mesh");
  }
  ctx.progress.Report(0.5);
  {
    const std::string morphDir = (fs::path(out) / "morph").string();
    ctx.outputs.PrepareDirectory(morphDir, "morph folder");
    const std::vector<double> times = MorphTimes(static_cast<int>(frames));
    for (std::size_t k = 0; k < times.size(); ++k) {
      TriangleMesh m;
      m.V = MorphFrame(supine.V, pronePosition, times[k]);
      m.F = supine.F;
      m.pointData["SegmentId"] = supine.pointData.at("SegmentId");
      m.cellData["Dilatation"] = supine.cellData.at("Dilatation");
      io::WriteMesh(m, stage("morph/" + MorphFrameName(static_cast<int>(k), ".vtp")), "morph frame");
      ctx.progress.Report(0.5 + 0.45 * (k + 1.0) / times.size());
    }
  }
  ctx.progress.EndStage();

  // 3D pictures (paper Figs. 11-12): one fixed camera framing the supine surface, the prone one
  // and so every morph frame; each picture staged like every other output.
  ctx.progress.StartStage("Render3D", "rendering the 3D distortion, texture and morph pictures");
  json views3D;
  if (skip3DReason.empty()) {
    const SurfaceRenderOptions ro;  // 360 x 480: the colon is taller than wide from the front
    const std::array<double, 2> picture{static_cast<double>(ro.width), static_cast<double>(ro.height)};
    Eigen::MatrixXd framed(supine.V.rows() + pronePosition.rows() + prone.V.rows(), 3);
    framed << MorphFramingPoints(supine.V, pronePosition), prone.V;
    const SurfaceCamera camera = FrameSurface(framed, view3D, picture[0] / picture[1], 0.04);
    SurfaceRenderer renderer(ro);
    const double renders = 6.0 + frames;
    double done = 0;
    auto render = [&](const SurfaceScene& scene) {
      ColourImage im = renderer.Render(scene, camera);
      ctx.progress.Report(++done / renders);  // cancel point between pictures
      return im;
    };
    auto write = [&](const ColourImage& im, const std::string& name) {
      WriteBytes(EncodePng(im), stage(name));
      views3D["pictures"][name] = {im.width, im.height};
    };
    const std::string where = "; " + view3D.name + " view (LPS: looking along " +
                              (view3D.name == "anterior" ? std::string("+P, superior up, patient's right on the left") :
                               view3D.name == "posterior" ? std::string("-P, superior up, patient's right on the right") :
                               view3D.name == "superior" ? std::string("-S from the head, anterior up") :
                               std::string("the patient's side, superior up")) + ")";
    std::array<double, 5> widths{0, 0, 0, 0, 0};
    for (std::size_t k = 0; k < views.size(); ++k) widths[static_cast<std::size_t>(present[k])] = views[k].s.period;
    {
      const ColourImage k3 = render(ColouredSurface(supine.V, supine.F, K.col(0), 1.0, kHigh, ColourMapKind::Turbo));
      const ColourImage t3 = render(ColouredSurface(supine.V, supine.F, DistortionAngle(muArg.col(0)), -kPi / 2, kPi / 2, ColourMapKind::Hsv));
      write(WithCaption(SideBySide({Titled(k3, "dilatation K"), bar(ro.height, 1.0, kHigh, ColourMapKind::Turbo, "K", "%.3f"),
                                    Titled(t3, "angle theta"), bar(ro.height, -90.0, 90.0, ColourMapKind::Hsv, "deg", "%.0f")}),
                        "Distortion of the registration on the supine surface" + where),
            "distortion_3d.png");
    }
    const Eigen::VectorXd sWidth = SegmentWidths(supine, widths), pWidth = SegmentWidths(prone, widths);
    const TriangleMesh sDrawn = DrawnPart(supine, sWidth), pDrawn = DrawnPart(prone, pWidth);
    const Eigen::MatrixXd& sUV = PointArray(supine, "SupineFlatUV", 2, regWhat);
    const Eigen::MatrixXd& pUV = PointArray(prone, "SupineFlatUV", 2, "prone registration mesh '" + pronePath.string() + "'");
    {
      std::vector<ColourImage> s3, p3;
      for (SurfaceTextureKind kind : {SurfaceTextureKind::Checkerboard, SurfaceTextureKind::Circles}) {
        s3.push_back(render(TexturedSurface(sDrawn.V, sDrawn.F, sUV, sWidth, kind, textures)));
        p3.push_back(render(TexturedSurface(pDrawn.V, pDrawn.F, pUV, pWidth, kind, textures)));
      }
      write(WithCaption(SideBySide({StackColumn(s3, {"", ""}, "supine", 10, 0), StackColumn(p3, {"", ""}, "carried to prone", 10, 0)}),
                        "Textures of the supine flat domain, carried to prone" + where),
            "textures_3d.png");
    }
    // Morph frames: the supine checkerboard rides on the vertices from the supine to the prone shape.
    const std::vector<double> times = MorphTimes(static_cast<int>(frames));
    for (std::size_t k = 0; k < times.size(); ++k) {
      const Eigen::MatrixXd Vt = MorphFrame(supine.V, pronePosition, times[k]);
      char caption[96];
      std::snprintf(caption, sizeof caption, "Morph supine -> prone, t = %.2f (frame %zu of %zu)", times[k], k + 1, times.size());
      write(WithCaption(render(TexturedSurface(Vt, sDrawn.F, sUV, sWidth, SurfaceTextureKind::Checkerboard, textures)), caption),
            "morph/" + MorphFrameName(static_cast<int>(k), ".png"));
    }
    views3D["rendered"] = true;
    views3D["view"] = view3D.name;
    views3D["camera"] = {{"position", {camera.pose.position.x(), camera.pose.position.y(), camera.pose.position.z()}},
                         {"focalPoint", {camera.pose.focalPoint.x(), camera.pose.focalPoint.y(), camera.pose.focalPoint.z()}},
                         {"viewUp", {camera.pose.viewUp.x(), camera.pose.viewUp.y(), camera.pose.viewUp.z()}},
                         {"parallelScale", camera.parallelScale}, {"coordinateSystem", "LPS"}};
    views3D["renderSize"] = {ro.width, ro.height};
  } else {
    views3D["rendered"] = false;
    views3D["reason"] = skip3DReason;
    ctx.progress.Note("ColonFlatViews: 3D pictures (distortion_3d.png, textures_3d.png, morph/*.png) not made: " + skip3DReason +
                      "; distortion.vtp and morph/*.vtp hold the same views for Slicer");
  }
  const Correlation cR = FlatImageCorrelation(allSupine, allRegistered), cU = FlatImageCorrelation(allSupine, allUnregistered);
  json report;
  const json pictureSizes = segments["_pictures"];
  segments.erase("_pictures");
  report["segments"] = segments;
  report["pictures"] = pictureSizes;
  report["dilatation"] = Summary(dAll);
  report["curvatureCorrelation"] = {{"unregistered", cU.r}, {"registered", cR.r}};
  report["curvatureRange"] = {hRange[0], hRange[1]};
  report["pixelsPerUnit"] = ppu;
  report["morphFrames"] = frames;
  report["registrationMethod"] = regReport.method;
  report["views3D"] = views3D;
  report["features"] = {{"supine", sFoldsTotal}, {"prone", pFoldsTotal}, {"matched", matchedTotal}, {"found", foundTotal}};
  files.push_back("flatviews.json");
  report["files"] = files;
  {
    const std::string p = ctx.outputs.Stage((fs::path(out) / "flatviews.json").string(), "output flatviews.json");
    std::ofstream f(p);
    f << report.dump(2) << "\n";
    if (!f) throw InputError("output report", p, "cannot be written");
  }
  ctx.progress.EndStage();
  ctx.progress.Note("ColonFlatViews: " + std::to_string(views.size()) + " segments; curvature correlation supine/prone " +
                    cli::FormatNumber(cU.r) + " unregistered, " + cli::FormatNumber(cR.r) + " registered; K mean " +
                    cli::FormatNumber(dAll.mean) + " p99 " + cli::FormatNumber(dAll.p99) + " max " + cli::FormatNumber(dAll.max) +
                    "; " + std::to_string(matchedTotal) + " matched folds");
  ctx.SetReturn("segments", std::to_string(views.size()));
  ctx.SetReturn("meanDilatation", cli::FormatNumber(dAll.mean));
  ctx.SetReturn("unregisteredCorrelation", cli::FormatNumber(cU.r));
  ctx.SetReturn("registeredCorrelation", cli::FormatNumber(cR.r));
}

}  // namespace colonmap::modules
