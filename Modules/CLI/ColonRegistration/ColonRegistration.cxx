// ColonRegistration: two ColonFlattening folders -> the supine <-> prone map of the colon wall
// (issue 7, DESIGN §2.4). Thin: arguments, reading, Libs/Registration, combining the segments,
// writing.
#include "CLI/Format.h"
#include "CLI/ModuleRunner.h"
#include "Core/Error.h"
#include "Core/RunConcurrently.h"
#include "IO/ImageIO.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "IO/SegmentFile.h"
#include "IO/StageReports.h"
#include "IO/ToolkitThreads.h"
#include "Registration/EmbeddedProneMesh.h"
#include "Registration/FlatLocator.h"
#include "Registration/RegistrationReliability.h"
#include "Registration/SegmentRegistration.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <filesystem>
#include <memory>
#include <fstream>
#include <optional>

namespace {

using namespace colonmap;
using namespace colonmap::registration;
namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kNames[5] = {"A", "T", "D", "S", "R"};

struct ScanSegment {
  TriangleMesh flat;  // flat_X.vtp as read
  SegmentInput input;
  std::optional<Volume<float>> curvature;
};

const DataArray& Need(const TriangleMesh& m, const std::string& name, int cols, const std::string& what,
                      const std::string& path) {
  const auto it = m.pointData.find(name);
  if (it == m.pointData.end() || it->second.values.cols() != cols || it->second.values.rows() != m.V.rows())
    throw InputError(what, path, "needs point data " + name + " with " + std::to_string(cols) + " components");
  return it->second;
}

// Fills `s` in place: s.input points into s (its curvature image).
void ReadSegment(ScanSegment& s, const fs::path& dir, int id, const io::FlatteningReport& report, const std::string& scan) {
  const std::string X = kNames[id];
  const std::string path = (dir / ("flat_" + X + ".vtp")).string(), what = scan + " flat mesh " + X;
  s.flat = io::ReadMesh(path, what);
  if (s.flat.F.rows() == 0) throw InputError(what, path, "has no triangles");
  io::CheckSegmentId(s.flat, id, what, path);  // not renamed or swapped with another segment's file
  s.input.flat.uv = Need(s.flat, "FlatUV", 2, what, path).values;
  s.input.flat.position = Need(s.flat, "Position3D", 3, what, path).values;
  s.input.flat.F = s.flat.F;
  // v runs from the anal end: A's far end is the caecum, R's near end the anus (tips, not flexures).
  s.input.flexureAtEnd = {id != 4, id != 0};
  std::optional<double> reportedWidth;
  if (const auto it = report.segments.find(X); it != report.segments.end()) {
    reportedWidth = it->second.flatWidth;
    if (it->second.cut) s.input.cutTaenia = *it->second.cut;
  }
  s.input.flat.period = CheckedFlatPeriod(reportedWidth, s.input.flat.uv, s.input.flat.position, X,
                                          scan + " flattening report", (dir / "flattening.json").string());
  if (!(s.input.flat.period > 0)) throw InputError(what, path, "the width of the flat map is unknown (no flattening.json and no cut copies)");
  if (auto a = s.flat.pointData.find("CenterlineArcLength"); a != s.flat.pointData.end())
    s.input.arcLength = a->second.values.col(0);
  if (auto h = s.flat.pointData.find("MeanCurvature"); h != s.flat.pointData.end() && h->second.values.cols() == 1)
    s.input.meanCurvature = h->second.values.col(0);
  const fs::path image = dir / ("curvature_" + X + ".nrrd");
  if (fs::exists(image)) {
    s.curvature = io::ReadImage<float>(image.string(), scan + " curvature image " + X);
    s.input.curvature = &*s.curvature;
  }
}

// Whether the scan's flexures were chosen jointly with the other scan: ColonLandmarks records
// its choice (jointChoice, handed on by flattening.json; pairedWith empty when the scan was done
// alone). Without the record (segments made by other means, e.g. cut from a phantom's truth)
// nothing is known against them.
bool FlexuresJoint(const io::FlatteningReport& report) {
  if (!report.jointChoice) return true;
  const io::JointChoice& j = *report.jointChoice;
  return !j.pairedWith.empty() && j.consistent && !j.fallback;
}

io::FlatteningReport ReadReport(const fs::path& dir, const std::string& scan) {
  return io::ReadFlatteningReport((dir / "flattening.json").string(), scan + " flattening report");
}

// The segments (by index) shared out to two threads: the largest first, each to the thread with
// less so far, so that both end at about the same time.
std::array<std::vector<std::size_t>, 2> ShareBySize(const std::vector<double>& sizes) {
  std::vector<std::size_t> order(sizes.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return sizes[a] > sizes[b]; });
  std::array<std::vector<std::size_t>, 2> share;
  double load[2] = {0.0, 0.0};
  for (std::size_t k : order) {
    const int t = load[0] <= load[1] ? 0 : 1;
    share[t].push_back(k);
    load[t] += sizes[k];
  }
  return share;
}

// Concatenates meshes; arrays present with the same width in every part are kept.
TriangleMesh Combine(const std::vector<const TriangleMesh*>& parts) {
  TriangleMesh out;
  Eigen::Index nv = 0, nf = 0;
  for (const TriangleMesh* m : parts) {
    nv += m->V.rows();
    nf += m->F.rows();
  }
  out.V.resize(nv, 3);
  out.F.resize(nf, 3);
  std::map<std::string, DataArray> point = parts.front()->pointData, cell = parts.front()->cellData;
  auto keepCommon = [&](std::map<std::string, DataArray>& arrays, bool isPoint) {
    for (auto it = arrays.begin(); it != arrays.end();) {
      bool ok = true;
      for (const TriangleMesh* m : parts) {
        const auto& a = isPoint ? m->pointData : m->cellData;
        const auto f = a.find(it->first);
        ok = ok && f != a.end() && f->second.values.cols() == it->second.values.cols();
      }
      if (ok) {
        it->second.values.resize(isPoint ? nv : nf, it->second.values.cols());
        ++it;
      } else {
        it = arrays.erase(it);
      }
    }
  };
  keepCommon(point, true);
  keepCommon(cell, false);
  Eigen::Index v0 = 0, f0 = 0;
  for (const TriangleMesh* m : parts) {
    out.V.middleRows(v0, m->V.rows()) = m->V;
    out.F.middleRows(f0, m->F.rows()) = m->F.array() + static_cast<int>(v0);
    for (auto& [name, a] : point) a.values.middleRows(v0, m->V.rows()) = m->pointData.at(name).values;
    for (auto& [name, a] : cell) a.values.middleRows(f0, m->F.rows()) = m->cellData.at(name).values;
    v0 += m->V.rows();
    f0 += m->F.rows();
  }
  out.pointData = point;
  out.cellData = cell;
  return out;
}

// The 3D cut surface of a segment with its flat map's arrays: V = Position3D, SegmentId set.
TriangleMesh SurfaceOf(const ScanSegment& s, int id) {
  TriangleMesh m;
  m.V = s.input.flat.position;
  m.F = s.flat.F;
  for (const auto& [name, a] : s.flat.pointData)
    if (name != "Position3D" && name != "FlatUV") m.pointData[name] = a;
  m.pointData["SegmentId"] = DataArray{Eigen::VectorXd::Constant(m.V.rows(), id), true};
  return m;
}

void Run(cli::ModuleContext& ctx) {
  const std::string sdir = ctx.args.GetString("supineFlatteningDirectory"), pdir = ctx.args.GetString("proneFlatteningDirectory"),
                    out = ctx.args.GetString("outputDirectory");
  if (sdir.empty() || pdir.empty()) throw Error("flattening folders: both the supine and the prone folder are needed");
  if (out.empty()) throw Error("output folder: no folder given");
  for (const auto& [dir, scan] : {std::pair{sdir, "supine"}, std::pair{pdir, "prone"}})
    if (!fs::is_directory(dir))
      throw InputError(std::string(scan) + " flattening folder", dir, fs::exists(dir) ? "is not a folder" : "does not exist");
  const std::string methodName = ctx.args.GetString("method");
  const RegistrationMethod method = methodName == "centerline" ? RegistrationMethod::Centerline
                                    : methodName == "harmonic" ? RegistrationMethod::Harmonic
                                                               : RegistrationMethod::Conformal;
  const bool reportTimes = ctx.args.GetBool("reportTimes");
  ReliabilityOptions reliability;
  reliability.maxBound90Mm = ctx.args.GetDouble("reliableBoundMm");
  if (!(reliability.maxBound90Mm > 0)) throw Error("reliable bound: must be a positive number of mm (--reliableBoundMm)");
  HarmonicOptions harmonic;
  harmonic.curvatureAlignment = ctx.args.GetString("initialMap") != "affine";
  harmonic.folds.method = ctx.args.GetString("foldDetection") == "threshold" ? FoldDetection::Threshold : FoldDetection::GraphCut;
  harmonic.matching.method = ctx.args.GetString("matching") == "greedy" ? MatchingMethod::Greedy : MatchingMethod::Spectral;

  std::vector<int> present;
  std::vector<std::pair<std::string, double>> plan;
  for (int id = 0; id < 5; ++id) {
    const std::string name = "flat_" + std::string(kNames[id]) + ".vtp";
    const bool s = fs::is_regular_file(fs::path(sdir) / name), p = fs::is_regular_file(fs::path(pdir) / name);
    if (s != p)
      throw InputError(s ? "prone flattening folder" : "supine flattening folder", s ? pdir : sdir,
                       "has no " + name + " although the other scan has it (mismatched segments)");
    if (s) {
      present.push_back(id);
      plan.emplace_back(std::string("Segment ") + kNames[id],
                        static_cast<double>(fs::file_size(fs::path(sdir) / name) + fs::file_size(fs::path(pdir) / name)));
    }
  }
  if (present.empty()) throw InputError("supine flattening folder", sdir, "holds none of flat_A.vtp ... flat_R.vtp");
  // The host's stages: the segments (two at a time), their results in order, the files.
  double segmentsWeight = 0.0;
  for (const auto& [name, w] : plan) segmentsWeight += w;
  const io::FlatteningReport sreport = ReadReport(sdir, "supine"), preport = ReadReport(pdir, "prone");
  ctx.outputs.PrepareDirectory(out, "output folder");
  ctx.progress.Plan({{"Segments", segmentsWeight}, {"Results", 0.05 * segmentsWeight}, {"Write", 0.1 * plan.front().second}});

  std::vector<TriangleMesh> supineParts, proneParts;
  std::vector<SegmentRegistration> regs;
  const bool flexuresJoint = FlexuresJoint(sreport) && FlexuresJoint(preport);
  json segments;
  long flips = 0;
  MarkupList supineFeatures, proneFeatures;
  supineFeatures.name = "supine features";
  proneFeatures.name = "prone features";
  // The segments are registered independently: two at a time (Core/RunConcurrently.h), shared
  // out by size; everything else is done afterwards in segment order, so the outputs do not
  // depend on which thread registered what.
  struct Registered {
    ScanSegment s, p;
    SegmentRegistration r;
  };
  std::vector<std::unique_ptr<Registered>> done(present.size());
  // A segment's error is kept and the job goes on, so that the one reported is the first in
  // segment order, as when they ran one after the other.
  std::vector<std::exception_ptr> failed(present.size());
  std::vector<double> sizes;
  for (std::size_t k = 0; k < present.size(); ++k) sizes.push_back(plan[k].second);
  const std::array<std::vector<std::size_t>, 2> share = ShareBySize(sizes);
  auto job = [&](int t) {
    return [&, t](ProgressSink& sink) {
      double total = 0.0, before = 0.0;
      for (std::size_t k : share[t]) total += plan[k].second;
      for (std::size_t k : share[t]) {
        const int id = present[k];
        const std::string X = kNames[id];
        SubProgress segment(sink, before / total, (before + plan[k].second) / total);
        done[k] = std::make_unique<Registered>();
        Registered& d = *done[k];
        try {
          ReadSegment(d.s, sdir, id, sreport, "supine");
          ReadSegment(d.p, pdir, id, preport, "prone");
          segment.Report(0.2);
          try {
            SubProgress sub(segment, 0.2, 1.0);
            d.r = RegisterSegment(d.s.input, d.p.input, method, sub, harmonic);
          } catch (const Error& e) {
            throw Error("segment " + X + ": " + e.what());
          }
        } catch (const Error&) {
          failed[k] = std::current_exception();
        }
        before += plan[k].second;
      }
    };
  };
  ctx.progress.StartStage("Segments", "registering the segments, two at a time");
  io::PrepareToolkitsForThreads();
  RunConcurrently(job(0), job(1), ctx.progress);
  for (const std::exception_ptr& e : failed)
    if (e) std::rethrow_exception(e);
  ctx.progress.EndStage();
  ctx.progress.StartStage("Results", "per segment results, in order");
  for (std::size_t n = 0; n < present.size(); ++n) {
    const int id = present[n];
    const std::string X = kNames[id];
    const ScanSegment& s = done[n]->s;
    const ScanSegment& p = done[n]->p;
    SegmentRegistration& r = done[n]->r;
    supineParts.push_back(SurfaceOf(s, id));
    proneParts.push_back(SurfaceOf(p, id));
    TriangleMesh& sp = supineParts.back();
    TriangleMesh& pp = proneParts.back();
    sp.pointData["SupineFlatUV"] = DataArray{s.input.flat.uv, false};
    sp.pointData["ProneFlatUV"] = DataArray{r.forward.uv, false};
    sp.pointData["ProneBarycentric"] = DataArray{r.forward.bary, false};
    sp.pointData["PronePosition"] = DataArray{r.forward.position, false};
    sp.pointData["ProneTriangleId"] = DataArray{r.forward.face.cast<double>(), true};  // offset later
    Eigen::VectorXd absMu = r.mu.cwiseAbs(), argMu(r.mu.size());
    for (Eigen::Index f = 0; f < r.mu.size(); ++f) argMu(f) = std::arg(r.mu(f));
    const Eigen::VectorXd K = Dilatation(r.mu);
    const VertexUncertainty& U = r.uncertainty;
    sp.cellData["BeltramiAbs"] = DataArray{absMu, false};
    sp.cellData["BeltramiArg"] = DataArray{argMu, false};
    sp.cellData["Dilatation"] = DataArray{K, false};
    pp.pointData["ProneFlatUV"] = DataArray{p.input.flat.uv, false};
    pp.pointData["SupineFlatUV"] = DataArray{r.inverseSupineUV, false};
    pp.pointData["SupineBarycentric"] = DataArray{r.inverse.bary, false};
    pp.pointData["SupinePosition"] = DataArray{r.inverse.position, false};
    pp.pointData["SupineTriangleId"] = DataArray{r.inverse.face.cast<double>(), true};

    std::vector<double> k(K.data(), K.data() + K.size());
    std::sort(k.begin(), k.end());
    json j;
    j["method"] = methodName;
    if (method == RegistrationMethod::Harmonic) {
      json m = json::array();
      for (std::size_t k = 0; k < r.matches.size(); ++k) {
        const FoldFeature& a = r.supineFolds[r.matches[k].supine];
        const FoldFeature& b = r.proneFolds[r.matches[k].prone];
        const std::string label = "F" + X + std::to_string(k + 1);
        m.push_back({{"label", label}, {"supineUV", {a.centroid.x(), a.centroid.y()}}, {"proneUV", {b.centroid.x(), b.centroid.y()}},
                     {"score", r.matches[k].score}});
        supineFeatures.points.push_back({label, a.position, "fold centroid, segment " + X});
        proneFeatures.points.push_back({label, b.position, "fold centroid, segment " + X});
      }
      j["features"] = {{"supine", r.supineFolds.size()}, {"prone", r.proneFolds.size()}, {"matchedBeforeGuard", r.matchesBeforeGuard},
                       {"matched", r.matches.size()}, {"constraints", r.correction.constraintsUsed},
                       {"droppedByGuard", r.correction.droppedGroups.size()}, {"initialFlips", r.correction.initialFlips},
                       {"solves", r.correction.rounds}, {"hScale", r.correction.scale}, {"surfaceRetries", r.correction.surfaceRetries},
                       {"repairRounds", r.repairRounds}, {"repairedVertices", r.repairedVertices},
                       {"surfaceRepairedVertices", r.surfaceRepairedVertices}, {"matches", m}};
    }
    if (!r.warp.supineV.empty())
      j["alignment"] = {{"used", r.warped}, {"shiftOnly", r.warp.shiftOnly}, {"smoothSigmaRows", r.warp.smoothSigmaRows}, {"meanShift", r.warp.MeanShift()}, {"maxAlongDeviation", r.warp.MaxAlongDeviation()},
                        {"pathCorrelation", r.warp.pathCorrelation}, {"affineCorrelation", r.warp.affineCorrelation},
                        {"rows", r.warp.rows}};
    j["uncertainty"] = {{"pathCorrelation", U.segment.pathCorrelation}, {"droppedFraction", U.segment.droppedFraction},
                        {"matchesPer100mm", U.segment.matchesPer100mm}, {"curvatureAgreement", U.segment.curvatureAgreement},
                        {"lengthMismatch", U.segment.lengthMismatch}, {"deformationMm", U.segment.deformationMm},
                        {"mmPerFlatUnit", U.mmPerFlatUnit}};
    j["supineVertices"] = s.flat.V.rows();
    j["proneVertices"] = p.flat.V.rows();
    j["supineCut"] = s.input.cutTaenia;
    j["proneCut"] = p.input.cutTaenia;
    j["width"] = {s.input.flat.period, p.input.flat.period};
    j["shift"] = r.eta.shift;
    j["shiftFromCorrelation"] = r.shiftFromCorrelation;
    j["correlationShift"] = r.correlation.shift;
    j["correlation"] = {{"atShift", r.correlation.correlation}, {"atZero", r.correlation.correlationAtZero}};
    j["scale"] = r.eta.scale;
    j["flatFlips"] = r.flatFlips;
    j["surfaceFlips"] = r.surfaceFlips;
    j["outsideForward"] = r.forward.outside;
    j["outsideInverse"] = r.inverse.outside;
    j["maxOutsideDistance"] = std::max(r.forward.maxOutsideDistance, r.inverse.maxOutsideDistance);
    j["dilatation"] = {{"mean", K.mean()}, {"median", k[k.size() / 2]}, {"p99", k[(k.size() * 99) / 100]}, {"max", k.back()}};
    std::string steps;
    json times;
    for (const auto& [step, sec] : r.times) {
      times[step] = sec;
      steps += (steps.empty() ? "" : ", ") + step + " " + cli::FormatNumber(sec) + " s";
    }
    if (reportTimes) j["times"] = times;
    segments[X] = j;
    flips += r.flatFlips + r.surfaceFlips;
    const std::string featureNote =
        method == RegistrationMethod::Harmonic
            ? ", folds " + std::to_string(r.supineFolds.size()) + "/" + std::to_string(r.proneFolds.size()) + ", matched " +
                  std::to_string(r.matches.size()) + " (guard dropped " + std::to_string(r.correction.droppedGroups.size()) + ")"
            : std::string();
    ctx.progress.Note("ColonRegistration: segment " + X + featureNote + ": shift " + cli::FormatNumber(r.eta.shift) + " (correlation " +
                      cli::FormatNumber(r.correlation.shift) + "), scale " + cli::FormatNumber(r.eta.scale) + ", flips " +
                      std::to_string(r.flatFlips) + "/" + std::to_string(r.surfaceFlips) + ", K mean " +
                      cli::FormatNumber(K.mean()) + "; times: " + steps);
    regs.push_back(std::move(r));
    done[n].reset();
    ctx.progress.Report(static_cast<double>(n + 1) / present.size());
  }
  ctx.progress.EndStage();

  // Trust per segment, then per vertex (RegistrationReliability.h): an untrusted segment makes
  // the flexures at its ends suspect for its neighbours.
  std::vector<SegmentTrust> trust;
  for (const SegmentRegistration& r : regs) trust.push_back(JudgeSegment(r.uncertainty.segment, flexuresJoint));
  const auto untrustedId = [&](int id) {
    const auto it = std::find(present.begin(), present.end(), id);
    return it != present.end() && !trust[it - present.begin()].trusted;
  };
  std::string untrusted;
  for (std::size_t k = 0; k < present.size(); ++k) {
    const int id = present[k];
    const std::string X = kNames[id];
    SegmentRegistration& r = regs[k];
    // The v-min end borders the next segment towards the anus (id + 1), the v-max end the previous.
    const std::array<bool, 2> endSuspect = {r.uncertainty.segment.flexureAtEnd[0] && untrustedId(id + 1),
                                            r.uncertainty.segment.flexureAtEnd[1] && untrustedId(id - 1)};
    const Eigen::VectorXd trusted = TrustedVertices(r.uncertainty.components, trust[k].trusted, endSuspect, reliability);
    ApplyTrust(r.uncertainty, trusted);  // the untrusted points' bounds widen
    const VertexUncertainty& U = r.uncertainty;
    const Eigen::VectorXd reliable = ReliableVertices(trusted, U.bound90, reliability);
    // Uncertainty (RegistrationUncertainty.h): the model's value and its components, per vertex;
    // the prone side takes the supine values at each prone vertex's inverse image.
    const std::pair<const char*, const Eigen::VectorXd*> uarrays[] = {
        {"Uncertainty", &U.median}, {"Uncertainty90", &U.bound90}, {"UncertaintyLoo", &U.components.loo},
        {"UncertaintyNearMm", &U.components.nearMm}, {"UncertaintyCorrectionMm", &U.components.correctionMm},
        {"UncertaintyDilatation", &U.components.dilatation}, {"UncertaintyFlexureMm", &U.components.flexureMm},
        {"UncertaintyCurvature", &U.components.curvature}, {"UncertaintyScale", &U.components.scale},
        {"UncertaintyAlongMm", &U.components.alongMm}};
    for (const auto& [name, values] : uarrays) {
      supineParts[k].pointData[name] = DataArray{*values, false};
      proneParts[k].pointData[name] = DataArray{Interpolate(r.inverse, supineParts[k].F, *values), false};
    }
    supineParts[k].pointData["Trusted"] = DataArray{trusted, true};
    supineParts[k].pointData["Reliable"] = DataArray{reliable, true};
    // Prone vertices: as the supine point they come from (the nearest of the three).
    const auto toProne = [&](const Eigen::VectorXd& flag) -> Eigen::VectorXd {
      return Interpolate(r.inverse, supineParts[k].F, flag).col(0).unaryExpr([](double x) { return x >= 0.5 ? 1.0 : 0.0; });
    };
    proneParts[k].pointData["Trusted"] = DataArray{toProne(trusted), true};
    proneParts[k].pointData["Reliable"] = DataArray{toProne(reliable), true};
    json& j = segments[X];
    j["trusted"] = trust[k].trusted;
    j["untrustedBecause"] = trust[k].reasons;
    j["trustedFraction"] = trusted.size() ? trusted.mean() : 0.0;
    j["reliableFraction"] = reliable.size() ? reliable.mean() : 0.0;
    j["uncertainty"]["medianOfVertices"] = U.median.size() ? [&] {
      std::vector<double> v(U.median.data(), U.median.data() + U.median.size());
      std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
      return v[v.size() / 2];
    }() : 0.0;
    j["expectedErrorMm"] = j["uncertainty"]["medianOfVertices"];
    // Collapsed stretches bridged by virtual lumen (ColonSurface's Virtual array, where a scan has
    // one): the share of each scan's wall of this segment that its CT did not show.
    for (const auto& [part, key] : {std::pair{&supineParts[k], "supineVirtualFraction"}, std::pair{&proneParts[k], "proneVirtualFraction"}})
      if (const auto it = part->pointData.find("Virtual"); it != part->pointData.end() && it->second.values.rows() > 0)
        j[key] = (it->second.values.col(0).array() >= 0.5).cast<double>().mean();
    if (!trust[k].trusted) {
      untrusted += (untrusted.empty() ? "" : ",") + X;
      std::string why;
      for (const std::string& reason : trust[k].reasons) why += (why.empty() ? "" : "; ") + reason;
      ctx.progress.Note("ColonRegistration: WARNING: segment " + X + " cannot be trusted (" + why + "): its points are marked reliable=false");
    }
  }

  ctx.progress.StartStage("Write", "writing the registration");
  // Triangle ids index the combined meshes: add each segment's face offset.
  Eigen::Index sf = 0, pf = 0;
  for (std::size_t k = 0; k < supineParts.size(); ++k) {
    supineParts[k].pointData["ProneTriangleId"].values.array() += static_cast<double>(pf);
    proneParts[k].pointData["SupineTriangleId"].values.array() += static_cast<double>(sf);
    sf += supineParts[k].F.rows();
    pf += proneParts[k].F.rows();
  }
  std::vector<const TriangleMesh*> sptr, pptr;
  for (const auto& m : supineParts) sptr.push_back(&m);
  for (const auto& m : proneParts) pptr.push_back(&m);
  const TriangleMesh supine = Combine(sptr), prone = Combine(pptr);
  ctx.progress.Report(0.3);
  // registration.vtp carries the prone mesh too: one file is all ColonTransferPoints and
  // ColonEvaluateRegistration need (Slicer passes a model node as a lone renamed copy).
  io::FieldArrays proneCopy;
  EmbedProneMesh(prone, &proneCopy);
  io::WriteMesh(supine, ctx.outputs.Stage((fs::path(out) / "registration.vtp").string(), "output registration.vtp"),
                "registration", proneCopy);
  io::WriteMesh(prone, ctx.outputs.Stage((fs::path(out) / "registration_prone.vtp").string(), "output registration_prone.vtp"),
                "prone registration mesh");
  // The same two surfaces for the scene (Slicer's model nodes), when asked for.
  if (const std::string m = ctx.args.GetString("registrationModel"); !m.empty())
    io::WriteMesh(supine, ctx.outputs.Stage(m, "registration model"), "registration model", proneCopy);
  if (const std::string m = ctx.args.GetString("proneModel"); !m.empty())
    io::WriteMesh(prone, ctx.outputs.Stage(m, "prone surface model"), "prone surface model");
  const Eigen::VectorXd K = supine.cellData.at("Dilatation").values.col(0);
  json report;
  report["segments"] = segments;
  report["method"] = methodName;
  report["flippedTriangles"] = flips;
  report["supine"] = fs::path(sdir).filename().string();
  report["meanDilatation"] = K.mean();
  report["flexuresJoint"] = flexuresJoint;
  report["untrustedSegments"] = untrusted;
  report["reliableBoundMm"] = reliability.maxBound90Mm;
  if (method == RegistrationMethod::Harmonic) {
    io::WriteMarkups(supineFeatures, ctx.outputs.Stage((fs::path(out) / "supine_features.mrk.json").string(), "output supine_features.mrk.json"),
                     "supine features");
    io::WriteMarkups(proneFeatures, ctx.outputs.Stage((fs::path(out) / "prone_features.mrk.json").string(), "output prone_features.mrk.json"),
                     "prone features");
  }
  {
    const std::string p = ctx.outputs.Stage((fs::path(out) / "registration.json").string(), "output registration.json");
    std::ofstream f(p);
    report.erase("supine");
    f << report.dump(2) << "\n";
    if (!f) throw InputError("output report", p, "cannot be written");
  }
  ctx.progress.EndStage();
  if (flips > 0) ctx.progress.Note("ColonRegistration: WARNING: " + std::to_string(flips) + " flipped triangles");
  ctx.SetReturn("segments", std::to_string(present.size()));
  ctx.SetReturn("flippedTriangles", std::to_string(flips));
  ctx.SetReturn("meanDilatation", cli::FormatNumber(K.mean()));
  ctx.SetReturn("untrustedSegments", untrusted);
}

}  // namespace

COLONMAP_MODULE_BODY(ColonRegistration, Run)
