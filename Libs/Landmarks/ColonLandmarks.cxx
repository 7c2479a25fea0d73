#include "ColonLandmarks.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
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
Flexures FlexuresOnCentred(const Centerline& c, const FlexureOptions& options) {
  const Eigen::VectorXd arc = analysis::ArcLength(c.uncentred);
  Flexures f = FindFlexures(c.uncentred, arc, options);
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  for (int k = 0; k < 4; ++k) {
    const analysis::MidlineProjection p = analysis::ProjectToMidline(f.position[k].transpose(), c.points, po);
    f.arc[k] = p.arc(0);
    const Eigen::Index i = std::clamp<Eigen::Index>(p.segment(0), 0, c.points.rows() - 2);
    const double len = c.arc(i + 1) - c.arc(i), t = len > 0 ? std::clamp((f.arc[k] - c.arc(i)) / len, 0.0, 1.0) : 0.0;
    f.sample[k] = static_cast<int>(t < 0.5 ? i : i + 1);
    f.position[k] = ((1 - t) * c.points.row(i) + t * c.points.row(i + 1)).transpose();
  }
  return f;
}

}  // namespace

LandmarkResult FindLandmarks(TriangleMesh closed, const LandmarkOptions& o, ProgressSink& progress) {
  LandmarkResult r;
  using Clock = std::chrono::steady_clock;
  auto t0 = Clock::now();
  const auto lap = [&](const char* name) {
    const auto t = Clock::now();
    r.times.emplace_back(name, std::chrono::duration<double>(t - t0).count());
    t0 = t;
  };
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
    r.flippedOrientation = true;
  }
  lap("check");

  SubProgress pc(progress, 0.0, 0.4);
  Centerline c = ComputeCenterline(closed.V, closed.F, o.centerline, pc);
  // Orient from the anal end: the cecum end has the smaller x (patient right).
  if (c.points(0, 0) < c.points(c.points.rows() - 1, 0)) c = Reversed(c);
  r.centerline = c;
  lap("centerline");
  r.flexures = c.uncentred.rows() ? FlexuresOnCentred(c, o.flexures) : FindFlexures(c.points, c.arc, o.flexures);
  progress.Report(0.45);
  lap("flexures");
  SubProgress ps(progress, 0.45, 0.7);
  try {
    r.segments = SplitColon(closed, c.points, c.arc, r.flexures.arc, o.segments, ps);
  } catch (const Error& e) {
    std::string found;
    for (int k = 0; k < 4; ++k)
      found += std::string(k ? ", " : "") + Flexures::Names()[k] + " " + Fixed(r.flexures.arc[k], 0);
    throw Error(std::string(e.what()) + " (flexures at " + found + " mm of a " + Fixed(c.Length(), 0) +
                " mm centreline)");
  }
  lap("segments");
  SubProgress pt(progress, 0.7, 1.0);
  r.taeniae = FindTaeniae(r.segments, c.points, o.taeniae, pt);
  lap("taeniae");
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
  j["taeniaMethod"] = "fold-interruption phase tracking (mean curvature > 0 as folds); TO is the cut";
  j["times"] = nlohmann::ordered_json::object();
  if (withTimes)
    for (const auto& [name, sec] : r.times) j["times"][name] = sec;
  return j.dump(2) + "\n";
}

}  // namespace colonmap::landmarks
