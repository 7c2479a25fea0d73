#include "ColonLandmarks.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "Core/RunConcurrently.h"
#include "Landmarks/BridgedWall.h"
#include "Landmarks/LevelCentreline.h"
#include "Surface/MeshTopology.h"
#include "Surface/SignedVolume.h"

#include <Eigen/Geometry>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

namespace colonmap::landmarks {

namespace {

// Scales a sink's fractions into [from, to] of the parent's.
class SubProgress : public ProgressSink {
 public:
  SubProgress(ProgressSink& parent, double from, double to) : parent_(parent), from_(from), to_(to) {}
  void Report(double f) override { parent_.Report(from_ + (to_ - from_) * f); }

 private:
  ProgressSink& parent_;
  double from_, to_;
};

std::string Fixed(double v, int digits) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

// The flexure rules run on the level-set curve they were tuned on (its corner cutting is part of
// what they expect); each flexure is then carried to the nearest point of the centred curve.
Flexures FlexuresOnCentred(const ColonAxis& axis, const std::array<double, 4>& ruleArcs) {
  const Centerline& c = axis.centerline;
  const Eigen::MatrixXd& rule = axis.RuleCurve();
  const Eigen::VectorXd ruleArc = analysis::ArcLength(rule);
  Flexures f;
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d p = analysis::PointAtArc(rule, ruleArc, ruleArcs[k]);
    const analysis::MidlineProjection proj = analysis::ProjectToMidline(p.transpose(), c.points, po);
    f.arc[k] = proj.arc(0);
    const Eigen::Index i = std::clamp<Eigen::Index>(proj.segment(0), 0, c.points.rows() - 2);
    const double len = c.arc(i + 1) - c.arc(i), t = len > 0 ? std::clamp((f.arc[k] - c.arc(i)) / len, 0.0, 1.0) : 0.0;
    f.sample[k] = static_cast<int>(t < 0.5 ? i : i + 1);
    f.position[k] = ((1 - t) * c.points.row(i) + t * c.points.row(i + 1)).transpose();
  }
  return f;
}

// Mean distance to the nearest surface vertex of every 5th sample of a curve (a clearance to
// the wall, within half an edge).
double MeanClearance(const Eigen::MatrixXd& V, const Eigen::MatrixXd& curve) {
  double sum = 0.0;
  int n = 0;
  for (Eigen::Index i = 0; i < curve.rows(); i += 5, ++n)
    sum += std::sqrt((V.rowwise() - curve.row(i)).rowwise().squaredNorm().minCoeff());
  return n ? sum / n : 0.0;
}

// The centreline as the smoothed centroids of the along-colon function's level sets (from the
// anal end, f = 0), 1 mm apart; the geodesic curve `c` becomes `uncentred` (the flexure rules'
// curve). The tips (f = 0 and 1 on their discs) are not loops: the levels start just inside.
Centerline LevelSetCenterline(const TriangleMesh& closed, const Eigen::VectorXd& f, Centerline c,
                              const LandmarkOptions& o) {
  const int n = std::max(100, o.centreLevels);
  const Eigen::VectorXd levels = Eigen::VectorXd::LinSpaced(n, 0.5 / n, 1.0 - 0.5 / n);
  const LevelCentreline lc = ComputeLevelCentreline(closed.V, closed.F, f, levels, o.levelSmoothingMm);
  Centerline out;
  out.uncentred = c.points;
  out.points = ResamplePolyline(lc.points, o.centerline.outputStepMm);
  out.arc = analysis::ArcLength(out.points);
  out.endFirst = c.endFirst;
  out.endSecond = c.endSecond;
  out.clearanceBeforeMm = MeanClearance(closed.V, c.points);
  out.clearanceMm = MeanClearance(closed.V, out.points);
  return out;
}

using Clock = std::chrono::steady_clock;
// Appends (name, seconds since t0) to times and restarts t0.
void Lap(std::vector<std::pair<std::string, double>>& times, Clock::time_point& t0, const char* name) {
  const auto t = Clock::now();
  times.emplace_back(name, std::chrono::duration<double>(t - t0).count());
  t0 = t;
}

// Candidates on wall not seen (bridged collapsed stretches) are flagged for the joint choice.
void MarkBridgedCandidates(const TriangleMesh& closed, const Eigen::VectorXd& alongColon, const Eigen::MatrixXd& rule,
                           const Eigen::VectorXd& ruleArc, FlexureCandidates& candidates) {
  if (!closed.pointData.count("Virtual")) return;
  std::vector<FlexureCandidate*> all;
  for (auto& list : candidates.flexure)
    for (FlexureCandidate& c : list) all.push_back(&c);
  Eigen::MatrixXd at(static_cast<Eigen::Index>(all.size()), 3);
  for (std::size_t i = 0; i < all.size(); ++i) {
    const Eigen::Index j = std::clamp<Eigen::Index>(
        static_cast<Eigen::Index>(std::lower_bound(ruleArc.data(), ruleArc.data() + ruleArc.size(), all[i]->arc) - ruleArc.data()),
        0, rule.rows() - 1);
    at.row(static_cast<Eigen::Index>(i)) = rule.row(j);
  }
  const std::vector<bool> bridged = OnBridgedWall(closed, alongColon, at);
  for (std::size_t i = 0; i < all.size(); ++i) all[i]->bridged = bridged[i];
}

}  // namespace

ColonAxis FindColonAxis(TriangleMesh closed, const LandmarkOptions& o, ProgressSink& progress) {
  ColonAxis x;
  auto t0 = Clock::now();
  const surface::TopologyReport topo = surface::AnalyzeTopology(closed.F);
  if (!topo.IsClosedGenusZero())
    throw Error("not a closed colon surface (one closed, manifold, consistently oriented genus-0 component "
                "needed): " + topo.Summary());
  if (closed.F.rows() < o.minFaces)
    throw Error("the surface has " + std::to_string(closed.F.rows()) + " triangles, too few for a colon (at least " +
                std::to_string(o.minFaces) + ")");
  // Normals into the lumen: a closed surface oriented so has negative signed volume.
  if (surface::SignedVolume(closed.V, closed.F) > 0) {
    closed.F.col(1).swap(closed.F.col(2));
    x.flippedOrientation = true;
  }
  Lap(x.times, t0, "check");
  SubProgress pc(progress, 0.0, 0.7);
  CenterlineOptions co = o.centerline;
  if (o.levelSetCentreline) co.centre = false;  // replaced below
  Centerline c = ComputeCenterline(closed.V, closed.F, co, pc);
  // Orient from the anal end: the cecum end has the smaller x (patient right).
  if (c.points(0, 0) < c.points(c.points.rows() - 1, 0)) c = Reversed(c);
  Lap(x.times, t0, "centerline");
  x.alongColon = AlongColonFunction(closed.V, closed.F, c.endFirst, c.endSecond, o.endDiscMm);
  progress.Report(0.9);
  Lap(x.times, t0, "along-colon function");
  if (o.levelSetCentreline) {
    c = LevelSetCenterline(closed, x.alongColon, std::move(c), o);
    Lap(x.times, t0, "level-set centreline");
  }
  x.centerline = std::move(c);
  progress.Report(0.95);
  const Eigen::MatrixXd& rule = x.RuleCurve();
  const Eigen::VectorXd ruleArc = analysis::ArcLength(rule);
  x.candidates = FindFlexureCandidates(rule, ruleArc, o.flexures);
  MarkBridgedCandidates(closed, x.alongColon, rule, ruleArc, x.candidates);
  progress.Report(1.0);
  Lap(x.times, t0, "flexures");
  x.closed = std::move(closed);
  return x;
}

LandmarkResult FinishLandmarks(ColonAxis x, const std::array<double, 4>& ruleArcs, const LandmarkOptions& o,
                               ProgressSink& progress) {
  LandmarkResult r;
  r.times = x.times;
  auto t0 = Clock::now();
  r.flippedOrientation = x.flippedOrientation;
  r.flexures = FlexuresOnCentred(x, ruleArcs);
  const Centerline& c = x.centerline;
  SubProgress ps(progress, 0.0, 0.5);
  try {
    r.segments = SplitColon(x.closed, x.alongColon, c.points, c.arc, r.flexures.arc, o.segments, ps);
  } catch (const Error& e) {
    std::string found;
    for (int k = 0; k < 4; ++k)
      found += std::string(k ? ", " : "") + Flexures::Names()[k] + " " + Fixed(r.flexures.arc[k], 0);
    throw Error(std::string(e.what()) + " (flexures at " + found + " mm of a " + Fixed(c.Length(), 0) +
                " mm centreline)");
  }
  Lap(r.times, t0, "segments");
  SubProgress pt(progress, 0.5, 1.0);
  r.taeniae = FindTaeniae(r.segments, c.points, o.taeniae, pt);
  Lap(r.times, t0, "taeniae");
  r.centerline = std::move(x.centerline);
  r.alongColon = std::move(x.alongColon);
  return r;
}

LandmarkResult FindLandmarks(TriangleMesh closed, const LandmarkOptions& o, ProgressSink& progress) {
  SubProgress pa(progress, 0.0, 0.45), pf(progress, 0.45, 1.0);
  ColonAxis x = FindColonAxis(std::move(closed), o, pa);
  const std::array<double, 4> arcs = x.candidates.byDefault.arc;
  return FinishLandmarks(std::move(x), arcs, o, pf);
}

std::array<LandmarkResult, 2> FindLandmarksForPair(TriangleMesh a, TriangleMesh b, const std::array<std::string, 2>& names,
                                                  const LandmarkOptions& o, ProgressSink& progress) {
  // The two scans' own work runs concurrently (RunConcurrently); errors name the scan.
  std::array<ColonAxis, 2> x;
  TriangleMesh* in[2] = {&a, &b};
  const auto axis = [&](int k, ProgressSink& p) {
    try {
      x[k] = FindColonAxis(std::move(*in[k]), o, p);
    } catch (const Error& e) {
      throw Error(names[k] + " surface: " + e.what());
    }
  };
  SubProgress first(progress, 0.0, 0.6);
  RunConcurrently([&](ProgressSink& p) { axis(0, p); }, [&](ProgressSink& p) { axis(1, p); }, first);
  auto t0 = Clock::now();
  const Eigen::MatrixXd &ra = x[0].RuleCurve(), &rb = x[1].RuleCurve();
  const double la = analysis::ArcLength(ra)(ra.rows() - 1), lb = analysis::ArcLength(rb)(rb.rows() - 1);
  // Aligned on the centred curves, told in the rule curves' arcs: the corner-cutting curves pair
  // the bends less well (real-colon pairs, GCA and VHM seeds 1-8: 5.1 against 2.2 mm off at the
  // true flexures). The chosen flexures' gap between the scans (material mm, mean over HF, SF,
  // DSJ, RSJ and seeds 1-8) went VHM 4.15 -> 2.37, VHF 7.17 -> 3.30, GCA 1.89 -> 1.31.
  const CentrelineAlignment align = CentrelineAlignment(x[0].centerline.points, x[1].centerline.points, o.alignment)
                                        .InArcsOf(ArcMap(ra, x[0].centerline.points), ArcMap(rb, x[1].centerline.points));
  const JointFlexureChoice choice = ChooseFlexuresJointly(x[0].candidates, x[1].candidates, la, lb, align, names, o.joint);
  std::array<JointNote, 2> notes;
  for (int k = 0; k < 2; ++k) {
    notes[k].pairedWith = names[1 - k];
    notes[k].consistent = choice.consistent;
    notes[k].fallback = choice.fallback;
    notes[k].how = choice.how;
    notes[k].defaultDisagreementMm = choice.defaultDisagreementMm;
    notes[k].alignmentCost = align.meanCost;
    notes[k].ownRuleArc = FlexuresOnCentred(x[k], x[k].candidates.byDefault.arc).arc;
    for (int f = 0; f < 4; ++f)
      for (const FlexureCandidate& c : x[k].candidates.flexure[f])
        if (c.isDefault) notes[k].ownRuleBridged[f] = c.bridged;
  }
  std::vector<std::pair<std::string, double>> jointTime;
  Lap(jointTime, t0, "joint flexures");
  std::array<LandmarkResult, 2> r;
  const auto finish = [&](int k, ProgressSink& p) {
    x[k].times.push_back(jointTime.front());
    try {
      r[k] = FinishLandmarks(std::move(x[k]), choice.arc[k], o, p);
    } catch (const Error& e) {
      throw Error(names[k] + " surface: " + e.what());
    }
    r[k].joint = notes[k];
  };
  SubProgress second(progress, 0.6, 1.0);
  RunConcurrently([&](ProgressSink& p) { finish(0, p); }, [&](ProgressSink& p) { finish(1, p); }, second);
  return r;
}

MarkupList CenterlineMarkups(const LandmarkResult& r, double stepMm) {
  MarkupList m;
  m.type = "Curve";
  m.name = "centerline";
  const Centerline& c = r.centerline;
  const Eigen::Index n = c.points.rows();
  const double L = c.Length();
  const int k = std::max(2, static_cast<int>(std::round(L / stepMm)) + 1);
  Eigen::Index j = 0;
  for (int i = 0; i < k; ++i) {
    const double a = L * i / (k - 1);
    while (j + 1 < n - 1 && c.arc(j + 1) < a) ++j;
    const double len = c.arc(j + 1) - c.arc(j);
    const double u = len > 0 ? std::clamp((a - c.arc(j)) / len, 0.0, 1.0) : 0.0;
    ControlPoint p;
    p.label = "C-" + std::to_string(i);
    p.position = ((1 - u) * c.points.row(j) + u * c.points.row(j + 1)).transpose();
    p.description = "arcLength=" + Fixed(a, 2);
    m.points.push_back(p);
  }
  return m;
}

MarkupList FlexureMarkups(const LandmarkResult& r) {
  MarkupList m;
  m.type = "Fiducial";
  m.name = "flexures";
  for (int k = 0; k < 4; ++k) {
    ControlPoint p;
    p.label = Flexures::Names()[k];
    p.position = r.flexures.position[k];
    p.description = "arcLength=" + Fixed(r.flexures.arc[k], 2);
    m.points.push_back(p);
  }
  return m;
}

PolylineSet TaeniaPolylines(const LandmarkResult& r) {
  PolylineSet set;
  const std::size_t nl = r.taeniae.size();
  DataArray seg, cut, conf, vid;
  seg.integer = cut.integer = vid.integer = true;
  seg.values.resize(static_cast<Eigen::Index>(nl), 1);
  cut.values.resize(static_cast<Eigen::Index>(nl), 1);
  conf.values.resize(static_cast<Eigen::Index>(nl), 1);
  std::size_t total = 0;
  for (const Taenia& t : r.taeniae) total += t.vertices.size();
  vid.values.resize(static_cast<Eigen::Index>(total), 1);
  Eigen::Index row = 0;
  for (std::size_t i = 0; i < nl; ++i) {
    const Taenia& t = r.taeniae[i];
    const TriangleMesh& mesh = r.segments.segment[t.segment];
    Polyline line;
    line.name = t.name;
    line.points.resize(static_cast<Eigen::Index>(t.vertices.size()), 3);
    for (std::size_t k = 0; k < t.vertices.size(); ++k) {
      line.points.row(static_cast<Eigen::Index>(k)) = mesh.V.row(t.vertices[k]);
      vid.values(row++) = t.vertices[k];
    }
    set.lines.push_back(line);
    seg.values(static_cast<Eigen::Index>(i)) = t.segment;
    cut.values(static_cast<Eigen::Index>(i)) = t.isCut ? 1 : 0;
    conf.values(static_cast<Eigen::Index>(i)) = t.confidence;
  }
  set.cellData["SegmentId"] = seg;
  set.cellData["IsCut"] = cut;
  set.cellData["Confidence"] = conf;
  set.pointData["VertexId"] = vid;
  return set;
}

std::optional<CutTaenia> CutTaeniaOf(const PolylineSet& taeniae, int segment) {
  const auto seg = taeniae.cellData.find("SegmentId"), cut = taeniae.cellData.find("IsCut");
  const auto vid = taeniae.pointData.find("VertexId");
  if (seg == taeniae.cellData.end() || cut == taeniae.cellData.end() || vid == taeniae.pointData.end())
    throw Error("needs cell data SegmentId and IsCut and point data VertexId");
  Eigen::Index offset = 0;
  for (std::size_t l = 0; l < taeniae.lines.size(); ++l) {
    const Polyline& line = taeniae.lines[l];
    const Eigen::Index k = line.points.rows();
    if (std::lround(seg->second.values(l, 0)) == segment && std::lround(cut->second.values(l, 0)) == 1) {
      CutTaenia c{line.name, line.points, Eigen::VectorXi(k)};
      for (Eigen::Index i = 0; i < k; ++i) c.vertices(i) = static_cast<int>(std::lround(vid->second.values(offset + i, 0)));
      return c;
    }
    offset += k;
  }
  return std::nullopt;
}

std::string SummaryJson(const LandmarkResult& r, bool withTimes) {
  nlohmann::ordered_json j;
  const std::array<double, 6> bounds{0.0, r.flexures.arc[3], r.flexures.arc[2], r.flexures.arc[1], r.flexures.arc[0],
                                     r.centerline.Length()};
  for (int s = 0; s < 5; ++s) {
    nlohmann::ordered_json e;
    const int band = 5 - s;  // segment s lies between bounds[band - 1] and bounds[band]
    e["lengthMm"] = bounds[band] - bounds[band - 1];
    e["faces"] = r.segments.segment[s].F.rows();
    for (const Taenia& t : r.taeniae)
      if (t.segment == s && t.isCut) e["cutTaenia"] = t.name, e["taeniaConfidence"] = t.confidence;
    j["segments"][SegmentName(s)] = e;
  }
  for (int k = 0; k < 4; ++k) {
    j["flexures"][Flexures::Names()[k]] = {{"arcLengthMm", r.flexures.arc[k]},
                                           {"position", {r.flexures.position[k].x(), r.flexures.position[k].y(),
                                                         r.flexures.position[k].z()}}};
  }
  j["centerlineLengthMm"] = r.centerline.Length();
  j["centerlineClearanceMm"] = {{"levelSetCurve", r.centerline.clearanceBeforeMm}, {"centred", r.centerline.clearanceMm}};
  j["flippedInputOrientation"] = r.flippedOrientation;
  j["relabelledFaces"] = r.segments.relabelledFaces;
  if (r.joint) {
    const JointNote& n = *r.joint;
    nlohmann::ordered_json jn;
    jn["pairedWith"] = n.pairedWith;
    jn["consistent"] = n.consistent;
    jn["fallback"] = n.fallback;
    jn["alignmentCost"] = n.alignmentCost;
    for (int k = 0; k < 4; ++k)
      jn["flexures"][Flexures::Names()[k]] = {{"choice", n.how[k]},
                                              {"ownRulesArcLengthMm", n.ownRuleArc[k]},
                                              {"ownRulesDisagreementMm", n.defaultDisagreementMm[k]}};
    for (int k = 0; k < 4; ++k)  // only where it applies: a colon in one piece keeps its file
      if (n.ownRuleBridged[k]) jn["flexures"][Flexures::Names()[k]]["ownRulesOnBridgedWall"] = true;
    j["jointChoice"] = jn;
  } else {
    // One scan alone: its flexures come from its own rules (the registration will not trust them).
    j["jointChoice"] = {{"pairedWith", ""}, {"consistent", true}, {"fallback", false}};
  }
  j["taeniaMethod"] = "fold-interruption phase tracking (mean curvature > 0 as folds); TO is the cut";
  j["times"] = nlohmann::ordered_json::object();
  if (withTimes)
    for (const auto& [name, sec] : r.times) j["times"][name] = sec;
  return j.dump(2) + "\n";
}

}  // namespace colonmap::landmarks
