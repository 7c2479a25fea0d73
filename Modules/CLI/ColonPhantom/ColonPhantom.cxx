// ColonPhantom: a synthetic supine/prone CT colonography pair with exact ground truth
// (issue 3). Thin: options from the XML, the math in Libs/Phantom, files through Libs/IO.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Phantom/Phantom.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>

namespace {

namespace fs = std::filesystem;
using namespace colonmap;
using namespace colonmap::phantom;
using nlohmann::json;

PhantomOptions OptionsFrom(const cli::Arguments& args) {
  PhantomOptions o;
  o.seed = static_cast<std::uint32_t>(args.GetInt("seed"));
  o.deformation = args.GetDouble("deformation");
  o.fluid = !args.GetBool("noFluid");
  const std::vector<double> spacing = args.GetDoubleVector("spacing");
  if (spacing.size() != 3 || !(spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0))
    throw Error("parameter --spacing: expected three positive numbers x,y,z in mm");
  for (double h : spacing)
    if (h < 0.2 || h > 10.0) throw Error("parameter --spacing: each value must be within 0.2..10 mm");
  o.spacing = Eigen::Vector3d(spacing[0], spacing[1], spacing[2]);
  return o;
}


json SummaryJson(const DilatationSummary& d) {
  return {{"mean", d.mean}, {"median", d.median}, {"p90", d.p90}, {"max", d.max}, {"faces", d.count}};
}

json Describe(const PhantomOptions& o, const ColonAnatomy& a, const ScanGeometry& supine,
              const ScanGeometry& prone, const DilatationStats& k, const Volume<short>& ct) {
  json j;
  j["generator"] = "ColonPhantom";
  j["options"] = {{"seed", o.seed}, {"deformation", o.deformation}, {"fluid", o.fluid},
                  {"spacing", {o.spacing.x(), o.spacing.y(), o.spacing.z()}}};
  j["colonLengthMm"] = a.length;
  j["proneCenterlineLengthMm"] = prone.centerline.Length();
  const char* flexures[] = {"HF", "SF", "DSJ", "RSJ"};
  for (int f = 0; f < 4; ++f) {
    j["flexures"][flexures[f]] = {{"materialS", a.flexureS[f]},
                                  {"supineArcLength", supine.ArcLength(a.flexureS[f])},
                                  {"proneArcLength", prone.ArcLength(a.flexureS[f])}};
  }
  for (int s = 0; s < 5; ++s) {
    const double s0 = s == 0 ? 0.0 : a.flexureS[s - 1];
    const double s1 = s == 4 ? a.length : a.flexureS[s];
    j["segments"][SegmentName(s)] = {
        {"materialS", {s0, s1}},
        {"supineLengthMm", supine.ArcLength(s1) - supine.ArcLength(s0)},
        {"proneLengthMm", prone.ArcLength(s1) - prone.ArcLength(s0)},
        {"baseRadiusMm", a.BaseRadius(0.5 * (s0 + s1))},
        {"dilatation", SummaryJson(k.segment[s])}};
  }
  j["dilatation"] = SummaryJson(k.all);
  j["dilatationNote"] = "K = sigma_max/sigma_min of the supine-to-prone map of each true-wall triangle";
  json polyps = json::array();
  for (const auto& p : a.polyps)
    polyps.push_back({{"label", p.label}, {"type", p.pedunculated ? "pedunculated" : "sessile"},
                      {"diameterMm", p.diameter}, {"heightMm", p.height}, {"materialS", p.s},
                      {"materialTheta", p.theta}, {"segment", SegmentName(a.SegmentOf(p.s))}});
  j["polyps"] = polyps;
  j["folds"] = a.folds.size();
  j["taeniae"] = {"TL", "TO", "TM"};
  j["evaluationPoints"] = a.evaluationSites.size();
  for (const ScanGeometry* scan : {&supine, &prone}) {
    json pools = json::array();
    for (const auto& pool : scan->pools)
      pools.push_back({{"arcLength", {pool.u0, pool.u1}}, {"levelHeightMm", pool.level}});
    j[scan == &supine ? "supine" : "prone"] = {{"fluidPools", pools}, {"fluidHU", scan->fluidHU},
                                               {"gravity", scan == &supine ? "+y (posterior)" : "-y (anterior)"}};
  }
  j["ct"] = {{"size", {ct.size[0], ct.size[1], ct.size[2]}},
             {"origin", {ct.origin.x(), ct.origin.y(), ct.origin.z()}},
             {"airHU", o.tissue.airHU}, {"fatHU", o.tissue.fatHU}, {"wallHU", o.tissue.wallHU},
             {"wallThicknessMm", o.tissue.wallThicknessMm}, {"noiseSigmaHU", o.tissue.noiseSigmaHU}};
  return j;
}

void Run(cli::ModuleContext& ctx) {
  const PhantomOptions options = OptionsFrom(ctx.args);
  const std::string out = ctx.args.GetString("outputDirectory");
  if (out.empty()) throw Error("parameter --outputDirectory: an output folder is required");
  // Checked first, so that a bad folder fails before minutes of work.
  ctx.outputs.PrepareDirectory(out, "output folder");
  ctx.progress.Plan({{"Anatomy", 1}, {"Truth surfaces", 2}, {"Supine CT", 20}, {"Prone CT", 20},
                     {"Writing", 10}});

  ctx.progress.StartStage("Anatomy", "seeded colon anatomy and its supine and prone embeddings");
  const ColonAnatomy anatomy = MakeAnatomy(options);
  const ScanGeometry supine = MakeScan(anatomy, Posture::Supine, options);
  ctx.progress.Report(0.5);
  const ScanGeometry prone = MakeScan(anatomy, Posture::Prone, options);
  ctx.progress.EndStage();

  ctx.progress.StartStage("Truth surfaces", "true walls and the dilatation of the deformation");
  const TriangleMesh supineWall = TrueWall(supine, options);
  ctx.progress.Report(0.4);
  const TriangleMesh proneWall = TrueWall(prone, options);
  ctx.progress.Report(0.8);
  const DilatationStats dilatation =
      SummarizeDilatation(FaceDilatation(supineWall, proneWall), FaceSegments(supineWall));
  ctx.progress.EndStage();

  ctx.progress.StartStage("Supine CT", "synthetic CT, supine");
  const Volume<short> supineCT = SynthesizeCT(supine, options, ctx.progress);
  ctx.progress.EndStage();
  ctx.progress.StartStage("Prone CT", "synthetic CT, prone");
  const Volume<short> proneCT = SynthesizeCT(prone, options, ctx.progress);
  ctx.progress.EndStage();

  ctx.progress.StartStage("Writing", "writing the phantom files");
  const auto file = [&](const std::string& name) {
    return ctx.outputs.Stage((fs::path(out) / name).string(), "output " + name);
  };
  // Uncompressed: the CT noise makes gzip slow and barely useful, and an uncompressed write
  // keeps Cancel prompt (ITK's writer cannot be interrupted).
  io::WriteImage(supineCT, file("supine.nrrd"), "supine CT", io::Compression::None);
  ctx.progress.Report(0.35);
  io::WriteImage(proneCT, file("prone.nrrd"), "prone CT", io::Compression::None);
  ctx.progress.Report(0.7);
  for (const ScanGeometry* scan : {&supine, &prone}) {
    const std::string p = scan == &supine ? "supine" : "prone";
    io::WriteMesh(scan == &supine ? supineWall : proneWall, file(p + "_truth.vtp"), p + " true wall");
    io::WriteMarkups(Polyps(*scan), file(p + "_polyps.mrk.json"), p + " polyps");
    io::WriteMarkups(EvaluationPoints(*scan), file(p + "_eval.mrk.json"), p + " evaluation points");
    io::WriteMarkups(ToMarkups(CenterlineSamples(*scan, 5.0)), file(p + "_centerline.mrk.json"), p + " centerline");
    io::WriteMarkups(Flexures(*scan), file(p + "_flexures.mrk.json"), p + " flexures");
    PolylineSet taeniae;
    for (const CurveSamples& t : Taeniae(*scan, 2.0)) taeniae.lines.push_back({t.name, t.points, false});
    io::WritePolylines(taeniae, file(p + "_taeniae.vtp"), p + " taeniae");
    ctx.progress.Report(scan == &supine ? 0.85 : 0.95);
  }
  io::WriteText(Describe(options, anatomy, supine, prone, dilatation, supineCT).dump(2) + "\n",
                file("truth.json"), "truth.json");
  ctx.progress.EndStage();

  ctx.SetReturn("colonLength", cli::FormatFixed(anatomy.length, 1));
  ctx.SetReturn("polypCount", std::to_string(anatomy.polyps.size()));
  ctx.progress.Note("ColonPhantom: colon " + cli::FormatFixed(anatomy.length, 0) + " mm, " +
                    std::to_string(anatomy.polyps.size()) + " polyps, dilatation K p90 " +
                    cli::FormatFixed(dilatation.all.p90, 2) + ", written to " + out);
}

}  // namespace

COLONMAP_MODULE_BODY(ColonPhantom, Run)
