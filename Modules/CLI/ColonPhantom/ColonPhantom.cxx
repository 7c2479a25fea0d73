// ColonPhantom: a synthetic supine/prone CT colonography pair with exact ground truth
// (issue 3). Thin: options from the XML, the math in Libs/Phantom, files through Libs/IO.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "IO/ImageIO.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "IO/NodeFiles.h"
#include "Phantom/Phantom.h"
#include "RealColon/RealColonPhantom.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <functional>
#include <map>

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
  o.collapses = args.GetInt("collapse");
  if (o.collapses < 0 || o.collapses > 4) throw Error("parameter --collapse: expected 0..4 collapsed stretches");
  const std::vector<double> spacing = args.GetDoubleVector("spacing");
  if (spacing.size() != 3 || !(spacing[0] > 0 && spacing[1] > 0 && spacing[2] > 0))
    throw Error("parameter --spacing: expected three positive numbers x,y,z in mm");
  for (double h : spacing)
    if (h < 0.2 || h > 10.0) throw Error("parameter --spacing: each value must be within 0.2..10 mm");
  o.spacing = Eigen::Vector3d(spacing[0], spacing[1], spacing[2]);
  return o;
}


// truth.json's collapsed stretches (issue 21), when there are any.
void AddCollapses(json& j, const std::vector<CollapsedStretch>& collapses, const std::function<double(double)>& supineArc,
                  const std::function<double(double)>& proneArc) {
  if (collapses.empty()) return;
  json list = json::array();
  for (const CollapsedStretch& c : collapses) {
    json scans = json::array();
    if (c.supine) scans.push_back("supine");
    if (c.prone) scans.push_back("prone");
    list.push_back({{"materialS", {c.s0, c.s1}}, {"segment", SegmentName(c.segment)}, {"scans", scans},
                    {"supineArcLength", {supineArc(c.s0), supineArc(c.s1)}},
                    {"proneArcLength", {proneArc(c.s0), proneArc(c.s1)}}});
  }
  j["collapses"] = list;
  j["collapsesNote"] = "the lumen is closed (no air, wall touching) over these stretches in the scans named";
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
  AddCollapses(j, a.collapses, [&](double s) { return supine.ArcLength(s); }, [&](double s) { return prone.ArcLength(s); });
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

json StatsJson(const realcolon::Displacement& d) {
  return {{"mean", d.mean}, {"median", d.median}, {"p90", d.p90}, {"max", d.max}, {"points", d.count}};
}

json DescribeReal(const PhantomOptions& o, const realcolon::RealColonOptions& ro, const realcolon::RealColonPair& p,
                  const Volume<short>& ct) {
  using realcolon::RealColonScan;
  const realcolon::TubeMaterial& m = p.material;
  json j;
  j["generator"] = "ColonPhantom --realColon";
  j["source"] = {{"name", p.source.name}, {"credit", p.source.credit}, {"notes", p.source.notes},
                 {"translationMm", {p.translation.x(), p.translation.y(), p.translation.z()}}};
  j["options"] = {{"seed", o.seed}, {"deformation", o.deformation}, {"fluid", o.fluid},
                  {"spacing", {o.spacing.x(), o.spacing.y(), o.spacing.z()}}, {"trueWallGridMm", ro.lumen.gridMm}};
  j["colonLengthMm"] = m.length;
  j["proneCenterlineLengthMm"] = p.prone.arc(p.prone.arc.size() - 1);
  const char* flexures[] = {"HF", "SF", "DSJ", "RSJ"};
  for (int f = 0; f < 4; ++f) {
    const double s = p.flexureS[static_cast<std::size_t>(f)];
    j["flexures"][flexures[f]] = {{"materialS", s}, {"supineArcLength", p.supine.ArcOfS(m, s)},
                                  {"proneArcLength", p.prone.ArcOfS(m, s)}, {"source", p.source.flexureSource[static_cast<std::size_t>(f)]}};
  }
  for (int k = 0; k < 5; ++k) {
    const double s0 = k == 0 ? 0.0 : p.flexureS[static_cast<std::size_t>(k - 1)];
    const double s1 = k == 4 ? m.length : p.flexureS[static_cast<std::size_t>(k)];
    j["segments"][SegmentName(k)] = {
        {"materialS", {s0, s1}},
        {"supineLengthMm", p.supine.ArcOfS(m, s1) - p.supine.ArcOfS(m, s0)},
        {"proneLengthMm", p.prone.ArcOfS(m, s1) - p.prone.ArcOfS(m, s0)},
        {"proneStretch", p.proneStretch[static_cast<std::size_t>(k)]},
        {"dilatation", SummaryJson(p.dilatation.segment[static_cast<std::size_t>(k)])},
        {"noRegistration", StatsJson(p.displacementBySegment[static_cast<std::size_t>(k)])}};
  }
  j["dilatation"] = SummaryJson(p.dilatation.all);
  j["dilatationNote"] = "K = sigma_max/sigma_min of the supine-to-prone map of each true-wall triangle";
  j["noRegistration"] = StatsJson(p.displacement);
  j["noRegistrationNote"] = "|prone - supine| of the evaluation points (mm): the error of taking supine positions as prone";
  j["maxLocalStretch"] = p.maxLocalStretch;
  j["materialCoordinates"] = {
      {"method", "s: arc length of the centroids of the level sets of one harmonic function on the opened surface "
                 "(0 on the caecal loop, 1 on the anal loop); theta: angle in the centreline's rotation-minimising frame"},
      {"levels", m.levelF.size()}, {"harmonicExtrema", m.harmonicExtrema}, {"localExtrema", m.localExtrema},
      {"checkedLevels", m.checkedLevels}, {"maxCurvesPerLevel", m.maxCurvesPerLevel}};
  j["trueWall"] = {{"gridMm", ro.lumen.gridMm}, {"lumenMl", p.lumen.lumenMl},
                   {"handleVoxelsCut", p.lumen.handleVoxelsRemoved}, {"cavityVoxelsFilled", p.lumen.cavityVoxelsFilled},
                   {"wellComposedVoxels", p.lumen.wellComposedVoxels}, {"restoredVertices", p.lumen.restoredVertices},
                   {"faces", p.supine.wall.F.rows()}, {"vertices", p.supine.wall.V.rows()},
                   {"closedFaces", p.supine.closed.F.rows()}};
  j["embedding"] = {{"supineCrossingFacePairs", p.supine.selfIntersections},
                    {"proneCrossingFacePairs", p.prone.selfIntersections}};
  json polyps = json::array();
  for (const auto& q : p.polyps)
    polyps.push_back({{"label", q.label}, {"type", q.pedunculated ? "pedunculated" : "sessile"},
                      {"diameterMm", q.diameter}, {"heightMm", q.height}, {"materialS", q.s},
                      {"materialTheta", q.theta}, {"segment", SegmentName(q.segment)}});
  j["polyps"] = polyps;
  AddCollapses(j, p.collapses, [&](double s) { return p.supine.ArcOfS(m, s); }, [&](double s) { return p.prone.ArcOfS(m, s); });
  j["taeniae"] = nullptr;
  j["taeniaeNote"] = "not known on real colons; no taeniae files are written";
  j["evaluationPoints"] = p.sites.size();
  for (const RealColonScan* scan : {&p.supine, &p.prone}) {
    json pools = json::array();
    for (std::size_t k = 0; k < scan->pools.size(); ++k)
      pools.push_back({{"materialS", {scan->poolS[k].first, scan->poolS[k].second}}, {"levelHeightMm", scan->pools[k].level}});
    j[scan == &p.supine ? "supine" : "prone"] = {
        {"fluidPools", pools}, {"fluidHU", scan->fluidHU},
        {"gravity", scan == &p.supine ? "+y (posterior)" : "-y (anterior)"},
        {"axisToLevelCentroidsMaxMm", scan->axisToCentroids}};
  }
  j["ct"] = {{"size", {ct.size[0], ct.size[1], ct.size[2]}},
             {"origin", {ct.origin.x(), ct.origin.y(), ct.origin.z()}},
             {"airHU", p.tissue.airHU}, {"fatHU", p.tissue.fatHU}, {"wallHU", p.tissue.wallHU},
             {"wallThicknessMm", p.tissue.wallThicknessMm}, {"noiseSigmaHU", p.tissue.noiseSigmaHU},
             {"bodySemiAxesMm", {p.tissue.bodySemiAxisXMm, p.tissue.bodySemiAxisYMm}}};
  return j;
}

// The CTs (two stages) and the files of both phantoms in one order: the CTs, each posture's
// files (writeScan, given the staged path of a file name), truth.json (made after the CTs, whose
// grid it describes).
using StagedFile = std::function<std::string(const std::string&)>;
void WritePhantom(cli::ModuleContext& ctx, const std::string& out, const std::function<Volume<short>(Posture)>& makeCT,
                  const std::function<void(Posture, const StagedFile&)>& writeScan,
                  const std::function<json(const Volume<short>&)>& truth) {
  ctx.progress.StartStage("Supine CT", "synthetic CT, supine");
  const Volume<short> supineCT = makeCT(Posture::Supine);
  ctx.progress.EndStage();
  ctx.progress.StartStage("Prone CT", "synthetic CT, prone");
  const Volume<short> proneCT = makeCT(Posture::Prone);
  ctx.progress.EndStage();

  ctx.progress.StartStage("Writing", "writing the phantom files");
  std::map<std::string, std::string> staged;  // file name -> its temporary, for the scene outputs
  const StagedFile file = [&](const std::string& name) {
    return staged[name] = ctx.outputs.Stage((fs::path(out) / name).string(), "output " + name);
  };
  // Uncompressed: the CT noise makes gzip slow and barely useful, and an uncompressed write
  // keeps Cancel prompt (ITK's writer cannot be interrupted).
  io::WriteImage(supineCT, file("supine.nrrd"), "supine CT", io::Compression::None);
  ctx.progress.Report(0.35);
  io::WriteImage(proneCT, file("prone.nrrd"), "prone CT", io::Compression::None);
  ctx.progress.Report(0.7);
  for (const Posture posture : {Posture::Supine, Posture::Prone}) {
    writeScan(posture, file);
    ctx.progress.Report(posture == Posture::Supine ? 0.85 : 0.95);
  }
  io::WriteText(truth(supineCT).dump(2) + "\n", file("truth.json"), "truth.json");
  // The two CTs and the polyps as nodes for the scene, when asked for: copies of the folder's
  // files (already written under their temporary names), in the format each name asks for.
  for (const char* p : {"supine", "prone"}) {
    const std::string scan(p);
    if (const std::string node = ctx.args.GetString(scan + "Volume"); !node.empty())
      io::CopyImageFile<short>(staged.at(scan + ".nrrd"), ctx.outputs.Stage(node, scan + " CT volume"), scan + " CT volume");
    if (const std::string node = ctx.args.GetString(scan + "Polyps"); !node.empty())
      io::CopyNodeFile(io::NodeFileKind::Markups, staged.at(scan + "_polyps.mrk.json"), ctx.outputs.Stage(node, scan + " polyps"),
                       scan + " polyps");
  }
  ctx.progress.EndStage();
}

// The real-colon phantom (issue 17): same files as the tube's, no taeniae.
void RunReal(cli::ModuleContext& ctx, const PhantomOptions& options, const std::string& source, const std::string& out) {
  realcolon::RealColonOptions ro;
  ro.phantom = options;
  ro.lumen.gridMm = ctx.args.GetDouble("trueWallGrid");
  if (!(ro.lumen.gridMm >= 0.5 && ro.lumen.gridMm <= 4.0))
    throw Error("parameter --trueWallGrid: must be within 0.5..4 mm");
  ctx.progress.Plan({{"Real colon", 12}, {"Supine CT", 20}, {"Prone CT", 20}, {"Writing", 10}});
  ctx.progress.StartStage("Real colon", "real colon made genus 0, material coordinates, polyps, prone flow");
  realcolon::ColonSource src = realcolon::ReadColonSource(source);
  const realcolon::RealColonPair pair = realcolon::MakeRealColonPair(std::move(src), ro, ctx.progress);
  ctx.progress.EndStage();
  WritePhantom(
      ctx, out, [&](Posture posture) { return realcolon::RealColonCT(pair, posture, ro, ctx.progress); },
      [&](Posture posture, const StagedFile& file) {
        const std::string p = posture == Posture::Supine ? "supine" : "prone";
        io::WriteMesh(posture == Posture::Supine ? pair.supine.wall : pair.prone.wall, file(p + "_truth.vtp"), p + " true wall");
        io::WriteMarkups(realcolon::RealPolypMarkups(pair, posture), file(p + "_polyps.mrk.json"), p + " polyps");
        io::WriteMarkups(realcolon::RealEvaluationMarkups(pair, posture), file(p + "_eval.mrk.json"), p + " evaluation points");
        io::WriteMarkups(realcolon::RealCentrelineMarkups(pair, posture, 5.0), file(p + "_centerline.mrk.json"), p + " centerline");
        io::WriteMarkups(realcolon::RealFlexureMarkups(pair, posture), file(p + "_flexures.mrk.json"), p + " flexures");
      },
      [&](const Volume<short>& supineCT) { return DescribeReal(options, ro, pair, supineCT); });

  ctx.SetReturn("colonLength", cli::FormatFixed(pair.material.length, 1));
  ctx.SetReturn("polypCount", std::to_string(pair.polyps.size()));
  std::string times;
  for (const auto& [step, seconds] : pair.seconds) times += (times.empty() ? "" : ", ") + step + " " + cli::FormatFixed(seconds, 2) + " s";
  ctx.progress.Note("ColonPhantom: real colon " + pair.source.name + " (" + pair.source.credit + "): " +
                    cli::FormatFixed(pair.material.length, 0) + " mm, " + std::to_string(pair.polyps.size()) +
                    " polyps; no registration (supine positions as prone) " + cli::FormatFixed(pair.displacement.mean, 1) +
                    " mm mean; written to " + out);
  ctx.progress.Note("ColonPhantom: steps: " + times);
}

void Run(cli::ModuleContext& ctx) {
  const PhantomOptions options = OptionsFrom(ctx.args);
  const std::string out = ctx.args.GetString("outputDirectory");
  if (out.empty()) throw Error("parameter --outputDirectory: an output folder is required");
  // Checked first, so that a bad folder fails before minutes of work.
  ctx.outputs.PrepareDirectory(out, "output folder");
  const std::string real = ctx.args.GetString("realColon");
  if (!real.empty()) return RunReal(ctx, options, real, out);
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

  WritePhantom(
      ctx, out, [&](Posture posture) { return SynthesizeCT(posture == Posture::Supine ? supine : prone, options, ctx.progress); },
      [&](Posture posture, const StagedFile& file) {
        const ScanGeometry& scan = posture == Posture::Supine ? supine : prone;
        const std::string p = posture == Posture::Supine ? "supine" : "prone";
        io::WriteMesh(posture == Posture::Supine ? supineWall : proneWall, file(p + "_truth.vtp"), p + " true wall");
        io::WriteMarkups(Polyps(scan), file(p + "_polyps.mrk.json"), p + " polyps");
        io::WriteMarkups(EvaluationPoints(scan), file(p + "_eval.mrk.json"), p + " evaluation points");
        io::WriteMarkups(ToMarkups(CenterlineSamples(scan, 5.0)), file(p + "_centerline.mrk.json"), p + " centerline");
        io::WriteMarkups(Flexures(scan), file(p + "_flexures.mrk.json"), p + " flexures");
        PolylineSet taeniae;
        for (const CurveSamples& t : Taeniae(scan, 2.0)) taeniae.lines.push_back({t.name, t.points, false});
        io::WritePolylines(taeniae, file(p + "_taeniae.vtp"), p + " taeniae");
      },
      [&](const Volume<short>& supineCT) { return Describe(options, anatomy, supine, prone, dilatation, supineCT); });

  ctx.SetReturn("colonLength", cli::FormatFixed(anatomy.length, 1));
  ctx.SetReturn("polypCount", std::to_string(anatomy.polyps.size()));
  ctx.progress.Note("ColonPhantom: colon " + cli::FormatFixed(anatomy.length, 0) + " mm, " +
                    std::to_string(anatomy.polyps.size()) + " polyps, dilatation K p90 " +
                    cli::FormatFixed(dilatation.all.p90, 2) + ", written to " + out);
}

}  // namespace

COLONMAP_MODULE_BODY(ColonPhantom, Run)
