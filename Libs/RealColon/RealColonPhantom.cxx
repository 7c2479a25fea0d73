#include "RealColon/RealColonPhantom.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "Phantom/Collapse.h"
#include "Phantom/PoolPlacement.h"
#include "Phantom/Random.h"
#include "Phantom/SynthesizeCT.h"
#include "RealColon/MidlineAlignment.h"
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"
#include "Surface/SelfIntersection.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <deque>
#include <limits>
#include <numeric>

namespace colonmap::realcolon {
namespace {
using phantom::Posture;
using phantom::Rng;
constexpr double kPi = 3.14159265358979323846;

class StepTimer {
 public:
  explicit StepTimer(std::vector<std::pair<std::string, double>>& out) : out_(out) {}
  void Lap(const std::string& name) {
    const auto now = std::chrono::steady_clock::now();
    out_.emplace_back(name, std::chrono::duration<double>(now - last_).count());
    last_ = now;
  }

 private:
  std::vector<std::pair<std::string, double>>& out_;
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

Eigen::Index LevelIndex(const TubeMaterial& m, double s) {
  const double f = m.FOfS(s);
  return std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::lround(f * (m.levelF.size() - 1))), 0,
                                  m.levelF.size() - 1);
}

// Flexures on our centreline: the source midline (anus first) aligned in order to our
// centreline read from the anal end.
std::array<double, 4> FlexureS(const ColonSource& src, const TubeMaterial& m) {
  Eigen::MatrixXd points(4, 3);
  for (int k = 0; k < 4; ++k) points.row(k) = src.flexures[static_cast<std::size_t>(k)].transpose();
  analysis::ProjectionOptions nearest;
  nearest.excludeBeyondEnds = false;
  const Eigen::VectorXd arcs = analysis::ProjectToMidline(points, src.midline, nearest).arc;
  const Eigen::MatrixXd fromAnus = m.centroid.colwise().reverse();
  const Eigen::VectorXd matched = AlignAlongCurve(src.midline, fromAnus, arcs);
  std::array<double, 4> s{};
  for (int k = 0; k < 4; ++k) s[static_cast<std::size_t>(k)] = m.length - matched(k);
  const char* names[] = {"HF", "SF", "DSJ", "RSJ"};
  for (int k = 0; k < 4; ++k) {
    const double lo = k == 0 ? 0.0 : s[static_cast<std::size_t>(k - 1)];
    if (s[static_cast<std::size_t>(k)] < lo + 30.0 || s[static_cast<std::size_t>(k)] > m.length - 30.0)
      throw Error(std::string("real colon ") + src.name + ": the " + names[k] +
                  " does not follow the previous landmark along the colon by 30 mm or more");
  }
  return s;
}

// Body and field of view that hold both postures with margins.
phantom::TissueModel FitBody(const phantom::TissueModel& base, const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  phantom::TissueModel t = base;
  const double margin = base.bodyRimMm + base.wallThicknessMm + 15.0;
  double ax = base.bodySemiAxisXMm, by = base.bodySemiAxisYMm;
  const Eigen::RowVector3d lo = a.colwise().minCoeff().cwiseMin(b.colwise().minCoeff());
  const Eigen::RowVector3d hi = a.colwise().maxCoeff().cwiseMax(b.colwise().maxCoeff());
  ax = std::max(ax, std::max(-lo(0), hi(0)) + margin);
  by = std::max(by, std::max(-lo(1), hi(1)) + margin);
  // Grow both semi-axes until every point is inside the ellipse shrunk by the margin.
  for (const Eigen::MatrixXd* P : {&a, &b})
    for (Eigen::Index i = 0; i < P->rows(); ++i) {
      const double x = (*P)(i, 0) / (ax - margin), y = (*P)(i, 1) / (by - margin);
      const double q = x * x + y * y;
      if (q > 1.0) {
        const double g = std::sqrt(q);
        ax = (ax - margin) * g + margin;
        by = (by - margin) * g + margin;
      }
    }
  t.bodySemiAxisXMm = ax;
  t.bodySemiAxisYMm = by;
  const double zMargin = base.wallThicknessMm + 22.0;
  t.fieldOfViewMm = Eigen::Vector3d(2.0 * ax + 10.0, 2.0 * by + 10.0, hi(2) - lo(2) + 2.0 * zMargin);
  t.fieldOfViewCentre = Eigen::Vector3d(0.0, 0.0, 0.5 * (lo(2) + hi(2)));
  return t;
}

// The open tube of a closed surface, with the material arrays.
TriangleMesh WallOf(const TriangleMesh& closed, const TubeMaterial& m, const std::array<double, 4>& flexureS) {
  TriangleMesh wall;
  Eigen::MatrixXd V;
  surface::KeepFaces(closed.V, closed.F, m.tubeFace, V, wall.F);
  wall.V.resize(static_cast<Eigen::Index>(m.tubeVertex.size()), 3);
  for (std::size_t i = 0; i < m.tubeVertex.size(); ++i) wall.V.row(static_cast<Eigen::Index>(i)) = closed.V.row(m.tubeVertex[i]);
  DataArray s, theta, seg;
  s.values = m.s;
  theta.values = m.theta;
  seg.values.resize(m.s.size(), 1);
  seg.integer = true;
  for (Eigen::Index v = 0; v < m.s.size(); ++v) {
    int k = 0;
    while (k < 4 && m.s(v) >= flexureS[static_cast<std::size_t>(k)]) ++k;
    seg.values(v, 0) = k;
  }
  wall.pointData["MaterialS"] = std::move(s);
  wall.pointData["MaterialTheta"] = std::move(theta);
  wall.pointData["SegmentId"] = std::move(seg);
  return wall;
}

int SegmentOfS(const std::array<double, 4>& flexureS, double s) {
  int k = 0;
  while (k < 4 && s >= flexureS[static_cast<std::size_t>(k)]) ++k;
  return k;
}

// The polyp's bump on the surface V: its foot's rest positions moved along its axis by the
// profile (sessile: a dome; pedunculated: a taller, steep-sided column with a rounded top, as
// the tube's polyps) of its height.
void ApplyBump(Eigen::MatrixXd& V, const RealPolyp& p) {
  const Eigen::Vector3d apex = p.footRest.row(0).transpose();  // the foot starts at the apex vertex
  for (std::size_t i = 0; i < p.foot.size(); ++i) {
    const Eigen::Vector3d rest = p.footRest.row(static_cast<Eigen::Index>(i)).transpose(), d = rest - apex;
    const double planar = (d - d.dot(p.axis) * p.axis).norm();
    const double q2 = planar * planar / (p.footRadius * p.footRadius);
    Eigen::Vector3d x = rest;
    if (q2 < 1.0) {
      const double base = p.pedunculated ? 1.0 - q2 * q2 : 1.0 - q2;
      x += p.height * base * std::sqrt(base) * p.axis;
    }
    V.row(p.foot[i]) = x.transpose();
  }
}

// Polyps: 3-5, in A, T, D, S in turn, 25 mm or more from the flexures, on wall between folds (a
// vertex whose mean curvature is among the lowest third of the candidates: folds have the
// highest), each a radial bump of the wall along its own normal.
std::vector<RealPolyp> PlacePolyps(TriangleMesh& closed, const TubeMaterial& m, const std::array<double, 4>& flexureS,
                                   std::uint32_t seed) {
  Rng r(seed, 106);
  const int count = r.Integer(3, 5);
  const Eigen::MatrixXd normals = surface::VertexNormals(closed.V, closed.F);
  const Eigen::VectorXd H = surface::MeanCurvature(closed.V, closed.F);
  const double start[] = {0.0, flexureS[0], flexureS[1], flexureS[2]}, end[] = {flexureS[0], flexureS[1], flexureS[2], flexureS[3]};
  // Vertex adjacency of the closed surface (for the bump's connected foot).
  std::vector<std::vector<int>> adjacent(static_cast<std::size_t>(closed.V.rows()));
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) adjacent[closed.F(f, k)].push_back(closed.F(f, (k + 1) % 3)), adjacent[closed.F(f, (k + 1) % 3)].push_back(closed.F(f, k));
  std::vector<RealPolyp> polyps;
  for (int i = 0; i < count; ++i) {
    RealPolyp p;
    p.label = "P" + std::to_string(i + 1);
    p.segment = (i + static_cast<int>(seed)) % 4;
    const double s0 = start[p.segment] + 25.0, s1 = end[p.segment] - 25.0;
    const double target = s1 > s0 ? r.Uniform(s0, s1) : 0.5 * (start[p.segment] + end[p.segment]);
    std::vector<int> candidates;
    for (std::size_t v = 0; v < m.tubeVertex.size(); ++v) {
      if (std::fabs(m.s(static_cast<Eigen::Index>(v)) - target) > 12.0) continue;
      const Eigen::RowVector3d x = closed.V.row(m.tubeVertex[v]);
      bool clear = true;
      for (const RealPolyp& q : polyps) clear = clear && (x - closed.V.row(q.vertex)).norm() > 25.0;
      if (clear) candidates.push_back(static_cast<int>(v));
    }
    if (candidates.empty()) continue;
    std::sort(candidates.begin(), candidates.end(), [&](int a, int b) {
      const double ha = H(m.tubeVertex[a]), hb = H(m.tubeVertex[b]);
      return ha != hb ? ha < hb : a < b;
    });
    const std::size_t third = std::max<std::size_t>(1, candidates.size() / 3);
    const int tubeV = candidates[std::min(third - 1, static_cast<std::size_t>(r.Uniform() * third))];
    p.vertex = m.tubeVertex[static_cast<std::size_t>(tubeV)];
    p.s = m.s(tubeV);
    p.theta = m.theta(tubeV);
    p.diameter = r.Uniform(4.0, 15.0);
    p.pedunculated = (i == 1) || (i > 2 && r.Uniform() < 0.4);
    p.footRadius = p.pedunculated ? 0.55 * p.diameter : 0.6 * p.diameter;
    const Eigen::Index level = LevelIndex(m, p.s);
    p.height = std::min(p.pedunculated ? 1.3 * p.diameter : 0.5 * p.diameter, 0.45 * m.levelRadius(level));
    polyps.push_back(p);
  }
  // The bumps. A bump that would make the wall cross itself (a tall polyp next to a fold) is
  // lowered, by 30% at a time, or dropped.
  const Eigen::MatrixXd V0 = closed.V;
  std::vector<RealPolyp> kept;
  for (RealPolyp p : polyps) {
    const Eigen::Vector3d apex = V0.row(p.vertex).transpose();
    // Foot: the vertices connected to the apex within 1.3 foot radii; axis: their mean normal.
    std::vector<char> seen(static_cast<std::size_t>(V0.rows()), 0);
    std::deque<int> queue{p.vertex};
    seen[p.vertex] = 1;
    p.axis = Eigen::Vector3d::Zero();
    while (!queue.empty()) {
      const int v = queue.front();
      queue.pop_front();
      p.foot.push_back(v);
      p.axis += normals.row(v).transpose();
      for (int w : adjacent[v])
        if (!seen[w] && (V0.row(w).transpose() - apex).norm() < 1.3 * p.footRadius) seen[w] = 1, queue.push_back(w);
    }
    p.axis.normalize();
    p.footRest.resize(static_cast<Eigen::Index>(p.foot.size()), 3);
    for (std::size_t i = 0; i < p.foot.size(); ++i) p.footRest.row(static_cast<Eigen::Index>(i)) = V0.row(p.foot[i]);
    // Faces near the polyp, for the crossing check.
    const double reach = 1.3 * p.footRadius + p.height + 12.0;
    std::vector<int> nearFaces;
    for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
      if ((V0.row(closed.F(f, 0)).transpose() - apex).norm() < reach) nearFaces.push_back(static_cast<int>(f));
    Eigen::MatrixXi local(static_cast<Eigen::Index>(nearFaces.size()), 3);
    for (std::size_t i = 0; i < nearFaces.size(); ++i) local.row(static_cast<Eigen::Index>(i)) = closed.F.row(nearFaces[i]);
    bool placed = false;
    for (int attempt = 0; attempt < 6 && !placed; ++attempt) {
      if (attempt > 0) p.height *= 0.7;
      ApplyBump(closed.V, p);
      placed = surface::FindSelfIntersections(closed.V, local, 0).pairs == 0;
    }
    if (!placed) {
      p.height = 0.0;
      ApplyBump(closed.V, p);
      continue;
    }
    kept.push_back(p);
  }
  for (std::size_t i = 0; i < kept.size(); ++i) kept[i].label = "P" + std::to_string(i + 1);
  polyps = kept;
  return polyps;
}

// A polyp whose stalk crosses the wall after the flow (a tall column of long faces, bent by the
// flow's shear) is lowered on the supine surface and mapped again, by 30% at a time, or removed.
void LowerCrossingPolyps(RealColonPair& pair) {
  TriangleMesh& sup = pair.supine.closed;
  TriangleMesh& pro = pair.prone.closed;
  for (int round = 0; round < 6; ++round) {
    const std::vector<int> faces = surface::SelfIntersectingFaces(pro.V, pro.F);
    if (faces.empty()) return;
    std::vector<char> crossing(static_cast<std::size_t>(pro.V.rows()), 0);
    for (int f : faces)
      for (int c = 0; c < 3; ++c) crossing[static_cast<std::size_t>(pro.F(f, c))] = 1;
    bool changed = false;
    for (std::size_t i = 0; i < pair.polyps.size();) {
      RealPolyp& p = pair.polyps[i];
      bool hit = false;
      for (int v : p.foot) hit = hit || crossing[static_cast<std::size_t>(v)];
      if (!hit) {
        ++i;
        continue;
      }
      p.height = round < 5 ? 0.7 * p.height : 0.0;
      ApplyBump(sup.V, p);
      Eigen::MatrixXd P(static_cast<Eigen::Index>(p.foot.size()), 3);
      for (std::size_t k = 0; k < p.foot.size(); ++k) P.row(static_cast<Eigen::Index>(k)) = sup.V.row(p.foot[k]);
      const Eigen::MatrixXd Q = pair.flow.Apply(P);
      for (std::size_t k = 0; k < p.foot.size(); ++k) pro.V.row(p.foot[k]) = Q.row(static_cast<Eigen::Index>(k));
      changed = true;
      if (p.height == 0.0) pair.polyps.erase(pair.polyps.begin() + static_cast<long>(i));
      else ++i;
    }
    if (!changed) return;  // crossings elsewhere: the embedding check reports them
  }
}

// Evaluation points: stratified along s, uniform by area within a stratum, 3 mm or more beyond
// every polyp's foot.
std::vector<RealSite> PlaceSites(const TriangleMesh& closed, const TubeMaterial& m, const std::array<double, 4>& flexureS,
                                 const std::vector<RealPolyp>& polyps, int count, std::uint32_t seed) {
  Rng r(seed, 107);
  std::vector<RealSite> sites;
  if (count <= 0) return sites;
  // Tube faces by the s of their centroid, with cumulative areas.
  std::vector<int> faces;
  std::vector<double> faceS;
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f) {
    if (!m.tubeFace[static_cast<std::size_t>(f)]) continue;
    faces.push_back(static_cast<int>(f));
  }
  std::vector<int> closedToTube(static_cast<std::size_t>(closed.V.rows()), -1);
  for (std::size_t v = 0; v < m.tubeVertex.size(); ++v) closedToTube[m.tubeVertex[v]] = static_cast<int>(v);
  const auto sAt = [&](int v) { return m.s(closedToTube[v]); };
  for (int f : faces) faceS.push_back((sAt(closed.F(f, 0)) + sAt(closed.F(f, 1)) + sAt(closed.F(f, 2))) / 3.0);
  std::vector<std::size_t> order(faces.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return faceS[a] != faceS[b] ? faceS[a] < faceS[b] : a < b; });
  std::vector<double> sortedS(order.size()), cumArea(order.size() + 1, 0.0);
  for (std::size_t i = 0; i < order.size(); ++i) {
    const int f = faces[order[i]];
    sortedS[i] = faceS[order[i]];
    const Eigen::Vector3d a = closed.V.row(closed.F(f, 0)), b = closed.V.row(closed.F(f, 1)), c = closed.V.row(closed.F(f, 2));
    cumArea[i + 1] = cumArea[i] + 0.5 * (b - a).cross(c - a).norm();
  }
  const double L = m.length;
  for (int i = 0; i < count; ++i) {
    RealSite e;
    char buf[16];
    std::snprintf(buf, sizeof buf, "E%03d", i + 1);
    e.label = buf;
    const double lo = std::clamp((i + 0.1) * L / count, 2.0, L - 2.0), hi = std::clamp((i + 0.9) * L / count, 2.0, L - 2.0);
    const std::size_t a = static_cast<std::size_t>(std::lower_bound(sortedS.begin(), sortedS.end(), lo) - sortedS.begin());
    const std::size_t b = static_cast<std::size_t>(std::upper_bound(sortedS.begin(), sortedS.end(), hi) - sortedS.begin());
    if (b <= a) continue;
    for (int attempt = 0; attempt < 50; ++attempt) {
      const double pick = cumArea[a] + r.Uniform() * (cumArea[b] - cumArea[a]);
      std::size_t k = static_cast<std::size_t>(std::upper_bound(cumArea.begin() + static_cast<long>(a) + 1, cumArea.begin() + static_cast<long>(b) + 1, pick) - cumArea.begin()) - 1;
      k = std::clamp(k, a, b - 1);
      e.face = faces[order[k]];
      double u = r.Uniform(), w = r.Uniform();
      if (u + w > 1.0) u = 1.0 - u, w = 1.0 - w;
      e.barycentric = Eigen::Vector3d(1.0 - u - w, u, w);
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      double s = 0.0;
      for (int c = 0; c < 3; ++c) {
        x += e.barycentric(c) * closed.V.row(closed.F(e.face, c)).transpose();
        s += e.barycentric(c) * sAt(closed.F(e.face, c));
      }
      e.s = s;
      e.theta = m.Angle(x, s);
      bool clear = true;
      for (const RealPolyp& p : polyps) clear = clear && (x - closed.V.row(p.vertex).transpose()).norm() > p.footRadius + 3.0;
      if (clear) break;
    }
    e.segment = SegmentOfS(flexureS, e.s);
    sites.push_back(e);
  }
  return sites;
}

// Pools at the lowest places of the lumen floor along the colon, the tube phantom's rule
// (Phantom/PoolPlacement.h).
void MakePools(RealColonScan& scan, const TubeMaterial& m, std::uint32_t seed) {
  Rng rng(seed, scan.posture == Posture::Supine ? 201 : 202);
  scan.fluidHU = rng.Uniform(600.0, 900.0);
  const int wanted = rng.Integer(2, 4);
  // Floor height every 2 mm of s.
  const double du = 2.0, L = m.length;
  const int nu = static_cast<int>(std::floor(L / du)) + 1;
  std::vector<double> floorH(static_cast<std::size_t>(nu));
  std::vector<Eigen::Vector3d> floorP(static_cast<std::size_t>(nu));
  for (int i = 0; i < nu; ++i) {
    const Eigen::Index l = LevelIndex(m, std::min(i * du, L));
    floorP[i] = scan.centreline.lowest.row(l).transpose();
    floorH[i] = -scan.down.dot(floorP[i]);
  }
  const auto diameter = [&](int i) { return 2.0 * scan.centreline.radius(LevelIndex(m, i * du)); };
  for (const phantom::PoolPlace& p : phantom::PlacePools(floorH, du, diameter, wanted, rng)) {
    FluidPoolSpec pool;
    pool.seed = floorP[p.deepest] - 1.0 * scan.down;  // 1 mm above the floor, in the lumen
    pool.level = p.level;
    scan.pools.push_back(pool);
    scan.poolS.emplace_back(p.lo * du, std::min(L, p.hi * du));
  }
}

Displacement Summarize(std::vector<double> d) {
  Displacement out;
  out.count = d.size();
  if (d.empty()) return out;
  std::sort(d.begin(), d.end());
  double sum = 0.0;
  for (double v : d) sum += v;
  out.mean = sum / static_cast<double>(d.size());
  out.median = d[d.size() / 2];
  out.p90 = d[std::min(d.size() - 1, static_cast<std::size_t>(std::ceil(0.9 * static_cast<double>(d.size()))) - 1)];
  out.max = d.back();
  return out;
}

void CheckEmbedded(RealColonScan& scan, const std::string& what) {
  const surface::SelfIntersections si = surface::FindSelfIntersections(scan.closed.V, scan.closed.F);
  scan.selfIntersections = si.pairs;
  if (si.pairs)
    throw Error("real colon phantom: the " + what + " surface passes through itself (" + std::to_string(si.pairs) +
                " crossing face pairs)");
}

}  // namespace

double RealColonScan::ArcOfS(const TubeMaterial& m, double s) const {
  const double f = m.FOfS(s) * (m.levelF.size() - 1);
  const Eigen::Index i = std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::floor(f)), 0, m.levelF.size() - 2);
  const double t = std::clamp(f - static_cast<double>(i), 0.0, 1.0);
  return (1.0 - t) * arc(i) + t * arc(i + 1);
}

Eigen::Vector3d RealColonScan::CentrePointAtS(const TubeMaterial& m, double s) const {
  const double f = m.FOfS(s) * (m.levelF.size() - 1);
  const Eigen::Index i = std::clamp<Eigen::Index>(static_cast<Eigen::Index>(std::floor(f)), 0, m.levelF.size() - 2);
  const double t = std::clamp(f - static_cast<double>(i), 0.0, 1.0);
  return ((1.0 - t) * centreline.points.row(i) + t * centreline.points.row(i + 1)).transpose();
}

Eigen::Vector3d RealColonScan::SitePosition(const RealSite& site) const {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int c = 0; c < 3; ++c) x += site.barycentric(c) * closed.V.row(closed.F(site.face, c)).transpose();
  return x;
}

int RealColonPair::SegmentOf(double s) const { return SegmentOfS(flexureS, s); }

RealColonPair MakeRealColonPair(ColonSource source, const RealColonOptions& options, ProgressSink& progress) {
  RealColonPair pair;
  StepTimer timer(pair.seconds);
  const std::uint32_t seed = options.phantom.seed;
  progress.Report(0.0);

  // 1. Closed genus-0 lumen, centred.
  SubProgress lumenProgress(progress, 0.0, 0.3);
  pair.lumen = MakeTrueLumen(source.surface, options.lumen, lumenProgress);
  source.surface = TriangleMesh();
  TriangleMesh closed = std::move(pair.lumen.surface);
  const Eigen::RowVector3d lo = closed.V.colwise().minCoeff(), hi = closed.V.colwise().maxCoeff();
  pair.translation = -0.5 * (lo + hi).transpose();
  closed.V.rowwise() += pair.translation.transpose();
  source.midline.rowwise() += pair.translation.transpose();
  for (Eigen::Vector3d& f : source.flexures) f += pair.translation;
  timer.Lap("genus-0 lumen");
  progress.Report(0.3);

  // 2. Material coordinates; flexures.
  const Eigen::Vector3d anus = source.midline.row(0).transpose();
  const Eigen::Vector3d pole = source.midline.row(source.midline.rows() - 1).transpose();
  SubProgress materialProgress(progress, 0.3, 0.5);
  pair.material = MakeTubeMaterial(closed, pole, anus, options.material, materialProgress);
  pair.flexureS = FlexureS(source, pair.material);
  pair.source = std::move(source);
  timer.Lap("material coordinates");
  progress.Report(0.5);

  // 3. Polyps and evaluation points on the supine wall.
  RealColonScan& sup = pair.supine;
  sup.posture = Posture::Supine;
  sup.closed = pair.material.closed;
  pair.polyps = PlacePolyps(sup.closed, pair.material, pair.flexureS, seed);
  pair.sites = PlaceSites(sup.closed, pair.material, pair.flexureS, pair.polyps, options.phantom.evaluationPoints, seed);
  {
    // The tube phantom's draw of collapsed stretches, on this colon's flexures and length.
    phantom::ColonAnatomy frame;
    frame.length = pair.material.length;
    frame.flexureS = pair.flexureS;
    pair.collapses = phantom::DrawCollapses(frame, options.phantom.collapses, seed);
  }
  timer.Lap("polyps and evaluation points");
  progress.Report(0.55);

  // 4. The prone flow.
  FlowOptions fo;
  fo.deformation = options.phantom.deformation;
  pair.flow = MakeProneFlow(pair.material, pair.flexureS, seed, fo);
  timer.Lap("prone flow: frames");
  RealColonScan& pro = pair.prone;
  pro.posture = Posture::Prone;
  pro.closed.F = sup.closed.F;
  SubProgress flowProgress(progress, 0.55, 0.75);
  pro.closed.V = pair.flow.Apply(sup.closed.V, &flowProgress);
  LowerCrossingPolyps(pair);
  for (std::size_t i = 0; i < pair.polyps.size(); ++i) pair.polyps[i].label = "P" + std::to_string(i + 1);
  timer.Lap("prone flow: surface");
  sup.wall = WallOf(sup.closed, pair.material, pair.flexureS);
  pro.wall = WallOf(pro.closed, pair.material, pair.flexureS);
  timer.Lap("prone flow");
  progress.Report(0.8);

  // 5. Checks: both surfaces embedded.
  CheckEmbedded(sup, "supine");
  CheckEmbedded(pro, "prone");
  timer.Lap("embedding checks");
  progress.Report(0.9);

  // 6. Centrelines, gravity, pools, body.
  sup.down = Eigen::Vector3d(0, 1, 0);
  pro.down = Eigen::Vector3d(0, -1, 0);
  for (RealColonScan* scan : {&sup, &pro}) {
    // The axis is material: the supine level-set centreline and its image under the flow (the
    // prone level-set centroids follow it within a few mm, but tilt with the loops).
    scan->centreline = ComputeLevelCentreline(scan->wall.V, scan->wall.F, pair.material.f, pair.material.levelF,
                                              options.material.smoothingMm, scan->down);
    const Eigen::MatrixXd axis = scan == &sup ? pair.material.centroid : pair.flow.Apply(pair.material.centroid);
    scan->axisToCentroids = (axis - scan->centreline.points).rowwise().norm().maxCoeff();
    scan->centreline.points = axis;
    scan->arc = analysis::ArcLength(scan->centreline.points);
    MakePools(*scan, pair.material, seed);
    scan->noiseKey = phantom::Hash(seed, scan == &sup ? 11 : 12);
  }
  pair.tissue = FitBody(options.phantom.tissue, sup.closed.V, pro.closed.V);

  // 7. Truth statistics.
  pair.dilatation = phantom::SummarizeDilatation(phantom::FaceDilatation(sup.wall, pro.wall), phantom::FaceSegments(sup.wall));
  std::vector<double> all;
  std::array<std::vector<double>, 5> bySegment;
  for (const RealSite& e : pair.sites) {
    const double d = (pro.SitePosition(e) - sup.SitePosition(e)).norm();
    all.push_back(d);
    bySegment[static_cast<std::size_t>(e.segment)].push_back(d);
  }
  pair.displacement = Summarize(all);
  for (int k = 0; k < 5; ++k) pair.displacementBySegment[static_cast<std::size_t>(k)] = Summarize(bySegment[static_cast<std::size_t>(k)]);
  const TubeMaterial& m = pair.material;
  for (int k = 0; k < 5; ++k) {
    const double s0 = k == 0 ? 0.0 : pair.flexureS[static_cast<std::size_t>(k - 1)];
    const double s1 = k == 4 ? m.length : pair.flexureS[static_cast<std::size_t>(k)];
    pair.proneStretch[static_cast<std::size_t>(k)] = (pro.ArcOfS(m, s1) - pro.ArcOfS(m, s0)) / (sup.ArcOfS(m, s1) - sup.ArcOfS(m, s0));
  }
  for (double s = 10.0; s + 30.0 < m.length; s += 2.0) {
    const double stretch = (pro.ArcOfS(m, s + 20.0) - pro.ArcOfS(m, s)) / (sup.ArcOfS(m, s + 20.0) - sup.ArcOfS(m, s));
    pair.maxLocalStretch = std::max(pair.maxLocalStretch, std::fabs(stretch - 1.0));
  }
  timer.Lap("centrelines, pools, truth");
  progress.Report(1.0);
  return pair;
}

Volume<short> RealColonCT(const RealColonPair& pair, Posture posture, const RealColonOptions& options, ProgressSink& progress) {
  phantom::PhantomOptions o = options.phantom;
  o.tissue = pair.tissue;
  Volume<short> grid = phantom::CTGrid(o);
  const RealColonScan& scan = posture == Posture::Supine ? pair.supine : pair.prone;
  MeshScan ms;
  ms.lumen = &scan.closed;
  ms.down = scan.down;
  ms.pools = scan.pools;
  ms.fluidHU = scan.fluidHU;
  ms.noiseKey = scan.noiseKey;
  if (!pair.collapses.empty()) {
    ms.axis = scan.centreline.points;
    ms.axisS = pair.material.levelS;
  }
  for (const phantom::CollapsedStretch& c : pair.collapses)
    if (posture == Posture::Supine ? c.supine : c.prone) ms.collapsedS.emplace_back(c.s0, c.s1);
  SynthesizeMeshCT(ms, o, grid, progress);
  return grid;
}

MarkupList RealPolypMarkups(const RealColonPair& pair, Posture posture) {
  const RealColonScan& scan = posture == Posture::Supine ? pair.supine : pair.prone;
  MarkupList m;
  m.name = "Polyps";
  for (const RealPolyp& q : pair.polyps) {
    ControlPoint p;
    p.label = q.label;
    p.position = scan.closed.V.row(q.vertex).transpose();
    char buf[160];
    std::snprintf(buf, sizeof buf, "type=%s diameter=%.2f segment=%s s=%.4f theta=%.6f",
                  q.pedunculated ? "pedunculated" : "sessile", q.diameter, phantom::SegmentName(q.segment), q.s, q.theta);
    p.description = buf + phantom::CollapseNote(pair.collapses, q.s, posture);
    m.points.push_back(p);
  }
  return m;
}

MarkupList RealEvaluationMarkups(const RealColonPair& pair, Posture posture) {
  const RealColonScan& scan = posture == Posture::Supine ? pair.supine : pair.prone;
  MarkupList m;
  m.name = "Evaluation";
  for (const RealSite& e : pair.sites) {
    ControlPoint p;
    p.label = e.label;
    p.position = scan.SitePosition(e);
    char buf[96];
    std::snprintf(buf, sizeof buf, "segment=%s s=%.4f theta=%.6f", phantom::SegmentName(e.segment), e.s, e.theta);
    p.description = buf + phantom::CollapseNote(pair.collapses, e.s, posture);
    m.points.push_back(p);
  }
  return m;
}

MarkupList RealFlexureMarkups(const RealColonPair& pair, Posture posture) {
  const RealColonScan& scan = posture == Posture::Supine ? pair.supine : pair.prone;
  MarkupList m;
  m.name = "Flexures";
  for (int f = 0; f < 4; ++f) {
    const double s = pair.flexureS[static_cast<std::size_t>(f)];
    ControlPoint p;
    p.label = phantom::FlexureName(f);
    p.position = scan.CentrePointAtS(pair.material, s);
    char buf[96];
    std::snprintf(buf, sizeof buf, "s=%.4f u=%.4f", s, scan.ArcOfS(pair.material, s));
    p.description = buf;
    m.points.push_back(p);
  }
  return m;
}

MarkupList RealCentrelineMarkups(const RealColonPair& pair, Posture posture, double stepMm) {
  const RealColonScan& scan = posture == Posture::Supine ? pair.supine : pair.prone;
  MarkupList m;
  m.type = "Curve";
  m.name = "Centerline";
  const double L = pair.material.length;
  const int n = std::max(2, static_cast<int>(std::lround(L / std::max(stepMm, 1e-3))) + 1);
  for (int i = 0; i < n; ++i) {
    const double s = i + 1 == n ? L : L * i / (n - 1);
    ControlPoint p;
    p.label = "Centerline-" + std::to_string(i);
    p.position = scan.CentrePointAtS(pair.material, s);
    char buf[96];
    std::snprintf(buf, sizeof buf, "s=%.4f u=%.4f", s, scan.ArcOfS(pair.material, s));
    p.description = buf;
    m.points.push_back(p);
  }
  return m;
}

}  // namespace colonmap::realcolon
