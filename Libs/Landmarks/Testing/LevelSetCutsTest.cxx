// Segment cuts at level sets of the along-colon function (issue 19): on tubes where a cut by
// the nearest centreline point meets another loop of the colon, the five segments still come
// out as consecutive cylinders whose boundaries are disjoint loops at the requested places.
#include "Landmarks/AlongColonFunction.h"
#include "Landmarks/Centerline.h"
#include "Landmarks/ColonSegments.h"

#include "../../RealColon/Testing/TestShapes.h"
#include "Core/Error.h"
#include "Surface/MeshTopology.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace colonmap::landmarks {
namespace {

// Appends to p a straight run to `to` (1 mm steps) and a half turn of radius r about the axis y
// from the last point, bending toward +x.
void Straight(std::vector<Eigen::Vector3d>& p, const Eigen::Vector3d& to) {
  const Eigen::Vector3d from = p.back();
  const int n = std::max(1, static_cast<int>(std::ceil((to - from).norm())));
  for (int i = 1; i <= n; ++i) p.push_back(from + (to - from) * i / n);
}
void HalfTurn(std::vector<Eigen::Vector3d>& p, double r, bool down) {
  const Eigen::Vector3d c = p.back() + Eigen::Vector3d(r, 0, 0);
  for (int i = 1; i <= 40; ++i) {
    const double a = M_PI * i / 40.0;
    p.push_back(c + Eigen::Vector3d(-r * std::cos(a), 0, (down ? -1.0 : 1.0) * r * std::sin(a)));
  }
}
Eigen::MatrixXd ToMatrix(const std::vector<Eigen::Vector3d>& p) {
  Eigen::MatrixXd P(static_cast<Eigen::Index>(p.size()), 3);
  for (std::size_t i = 0; i < p.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
  return P;
}

// Which band (0..6) each face of `closed` falls in when faces take the arc of the centreline
// point nearest their centroid (the cut before issue 19); returns the number of face pairs
// sharing an edge whose bands are not the same or next to each other (cuts that meet).
int MeetingCutsByNearestPoint(const TriangleMesh& closed, const Centerline& c, const std::array<double, 6>& cuts) {
  Eigen::MatrixXd centroids(closed.F.rows(), 3);
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
    centroids.row(f) = (closed.V.row(closed.F(f, 0)) + closed.V.row(closed.F(f, 1)) + closed.V.row(closed.F(f, 2))) / 3.0;
  const Eigen::VectorXd a = NearestArcLength(centroids, c.points);
  std::vector<int> band(static_cast<std::size_t>(closed.F.rows()));
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
    band[f] = static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), a(f)) - cuts.begin());
  std::map<std::pair<int, int>, int> edgeFace;
  int meeting = 0;
  for (Eigen::Index f = 0; f < closed.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = closed.F(f, k), v = closed.F(f, (k + 1) % 3);
      const auto key = std::minmax(u, v);
      const auto it = edgeFace.find(key);
      if (it == edgeFace.end()) edgeFace[key] = static_cast<int>(f);
      else if (std::abs(band[it->second] - band[f]) > 1) ++meeting;
    }
  return meeting;
}

struct Cuts {
  ColonSegments segments;
  Centerline centerline;
  int meetingBefore = 0;
};

// Splits the tube around polyline P at the four cut arcs (increasing, from P's first end).
Cuts SplitAt(const Eigen::MatrixXd& P, const Eigen::VectorXd& radii, const std::array<double, 4>& cutArc) {
  TriangleMesh closed = realcolon::testing::TubeAround(P, radii, 1.0);
  NullProgress np;
  Cuts out;
  CenterlineOptions co;
  Centerline c = ComputeCenterline(closed.V, closed.F, co, np);
  // Run the centreline from P's first end.
  if ((c.points.row(0) - P.row(0)).norm() > (c.points.row(c.points.rows() - 1) - P.row(0)).norm()) c = Reversed(c);
  out.centerline = c;
  const Eigen::VectorXd f = AlongColonFunction(closed.V, closed.F, c.endFirst, c.endSecond, 5.0);
  const SegmentOptions so;
  out.meetingBefore = MeetingCutsByNearestPoint(
      closed, c, {so.capMm, cutArc[0], cutArc[1], cutArc[2], cutArc[3], c.Length() - so.capMm});
  // flexureArc is HF, SF, DSJ, RSJ: from the cecal end down.
  out.segments = SplitColon(closed, f, c.points, c.arc, {cutArc[3], cutArc[2], cutArc[1], cutArc[0]}, so, np);
  return out;
}

// Every segment is a cylinder (SplitColon checks it); here: the four cut loops are disjoint,
// each shared by exactly the two segments it separates, and lies at its cut: the mean arc
// length of its vertices (CenterlineArcLength) within tolMm of the requested cut.
void ExpectDisjointLoopsAt(const Cuts& r, const std::array<double, 4>& cutArc, double tolMm) {
  // Segment order from the anal end: R(4), S(3), D(2), T(1), A(0); cut i lies between
  // segment 4 - i and 3 - i.
  std::array<std::vector<std::set<int>>, 5> loops;  // per segment, its boundary loops as open-mesh vertex ids
  for (int s = 0; s < 5; ++s)
    for (const std::vector<int>& loop : surface::BoundaryLoops(r.segments.segment[s].F)) {
      std::set<int> ids;
      for (int v : loop) ids.insert(r.segments.openVertex[s][v]);
      loops[s].push_back(ids);
    }
  const Eigen::VectorXd& arc = r.segments.open.pointData.at("CenterlineArcLength").values.col(0);
  std::vector<std::set<int>> cutLoops;
  for (int i = 0; i < 4; ++i) {
    const int below = 4 - i, above = 3 - i;
    int shared = 0;
    for (const auto& a : loops[below])
      for (const auto& b : loops[above])
        if (a == b) {
          ++shared;
          cutLoops.push_back(a);
          double mean = 0.0;
          for (int v : a) mean += arc(v);
          mean /= static_cast<double>(a.size());
          EXPECT_NEAR(mean, cutArc[i], tolMm) << "cut " << i;
        }
    EXPECT_EQ(shared, 1) << "cut " << i << " is not one loop shared by its two segments";
  }
  for (std::size_t i = 0; i < cutLoops.size(); ++i)
    for (std::size_t j = i + 1; j < cutLoops.size(); ++j)
      for (int v : cutLoops[i]) EXPECT_FALSE(cutLoops[j].count(v)) << "cuts " << i << " and " << j << " meet";
}

TEST(LevelSetCuts, WideLoopTouchingANarrowOneGivesDisjointLoopsWhereNearestPointCutsMeet) {
  // A wide limb (radius 20, a caecum) down 150 mm, a half turn of radius 15, a narrow limb
  // (radius 8, a sigmoid) back up: axes 30 mm apart, walls 2 mm apart. The wide limb's wall
  // facing the narrow one is nearer the narrow limb's axis, so nearest-point cuts jump across.
  std::vector<Eigen::Vector3d> p{Eigen::Vector3d(0, 0, 150)};
  Straight(p, Eigen::Vector3d(0, 0, 0));
  const std::size_t bendFrom = p.size();
  HalfTurn(p, 15.0, true);
  const std::size_t bendTo = p.size();
  Straight(p, Eigen::Vector3d(30, 0, 150));
  const Eigen::MatrixXd P = ToMatrix(p);
  Eigen::VectorXd radii(P.rows());
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double t = std::clamp((static_cast<double>(i) - bendFrom) / static_cast<double>(bendTo - bendFrom), 0.0, 1.0);
    radii(i) = 20.0 + t * (8.0 - 20.0);
  }
  const double turn = M_PI * 15.0;
  const std::array<double, 4> cuts{40.0, 150.0 + turn + 40.0, 150.0 + turn + 80.0, 300.0 + turn - 40.0};
  const Cuts r = SplitAt(P, radii, cuts);
  EXPECT_GT(r.meetingBefore, 0);
  ExpectDisjointLoopsAt(r, cuts, 8.0);
}

TEST(LevelSetCuts, SelfTouchingCoilGivesDisjointLoopsAtTheirCuts) {
  // Four limbs 150 mm long whose walls are 1.5 mm apart (axes 21.5 mm, radius 10), joined by
  // half turns: a tortuous, self-touching tube; cuts on every limb and in a bend.
  std::vector<Eigen::Vector3d> p{Eigen::Vector3d(0, 0, 150)};
  for (int limb = 0; limb < 4; ++limb) {
    Straight(p, Eigen::Vector3d(p.back().x(), 0, limb % 2 == 0 ? 0.0 : 150.0));
    if (limb < 3) HalfTurn(p, 10.75, limb % 2 == 0);
  }
  const Eigen::MatrixXd P = ToMatrix(p);
  const double turn = M_PI * 10.75;
  const std::array<double, 4> cuts{75.0, 150.0 + turn + 75.0, 300.0 + 2 * turn - 5.0, 450.0 + 3 * turn - 75.0};
  const Cuts r = SplitAt(P, Eigen::VectorXd::Constant(P.rows(), 10.0), cuts);
  ExpectDisjointLoopsAt(r, cuts, 6.0);
}

TEST(LevelSetCuts, AlongColonArcLengthIsMonotoneInFAndIgnoresFarProjections) {
  // f from 0 to 1 over 1000 vertices, arc = 500 f, with 3% of the vertices projected onto a
  // far loop (arc + 300): the fit stays within 1 mm of 500 f and is non-decreasing in f.
  const int n = 1000;
  Eigen::VectorXd f(n), a(n);
  for (int i = 0; i < n; ++i) {
    f(i) = static_cast<double>((i * 7919) % n) / (n - 1);
    a(i) = 500.0 * f(i) + ((i % 33) == 0 ? 300.0 : 0.0);
  }
  const Eigen::VectorXd fit = AlongColonArcLength(f, a, 500.0, 50);
  std::vector<std::pair<double, double>> byF;
  for (int i = 0; i < n; ++i) byF.emplace_back(f(i), fit(i));
  std::sort(byF.begin(), byF.end());
  for (int i = 1; i < n; ++i) EXPECT_GE(byF[i].second, byF[i - 1].second - 1e-12);
  for (int i = 0; i < n; ++i)
    if (f(i) > 0.05 && f(i) < 0.95) {  // the end bins are pinned
      EXPECT_NEAR(fit(i), 500.0 * f(i), 1.0);
    }
  EXPECT_THROW(AlongColonArcLength(f, Eigen::VectorXd::Zero(3), 500.0), Error);
  // The ends are pinned to the centreline's ends even where the wall's nearest arc stops short
  // (a blunt tip): arcs 5..495 give a fit from 0 to 500.
  const Eigen::VectorXd shortArc = (a.array() - 300.0 * (a.array() > 500.5).cast<double>()).cwiseMax(5.0).cwiseMin(495.0);
  const Eigen::VectorXd pinned = AlongColonArcLength(f, shortArc, 500.0, 50);
  EXPECT_NEAR(pinned.minCoeff(), 0.0, 1e-9);
  EXPECT_NEAR(pinned.maxCoeff(), 500.0, 1e-9);
}

TEST(LevelSetCuts, AlongColonFunctionIsHarmonicBetweenItsEnds) {
  // A cylinder of radius 10 and length 200 closed by nothing: f between the two end rings is
  // linear in z (the harmonic function of a straight tube), within 0.01.
  const TriangleMesh c = realcolon::testing::Cylinder(10.0, 200.0, 48, 200);
  std::vector<int> bottom, top;
  for (Eigen::Index v = 0; v < c.V.rows(); ++v) {
    if (c.V(v, 2) < 1e-9) bottom.push_back(static_cast<int>(v));
    if (c.V(v, 2) > 200.0 - 1e-9) top.push_back(static_cast<int>(v));
  }
  const Eigen::VectorXd f = AlongColonFunction(c.V, c.F, bottom, top);
  for (Eigen::Index v = 0; v < c.V.rows(); ++v) EXPECT_NEAR(f(v), c.V(v, 2) / 200.0, 0.01);
  EXPECT_THROW(AlongColonFunction(c.V, c.F, bottom, bottom), Error);
  EXPECT_THROW(AlongColonFunction(c.V, c.F, {}, top), Error);
}

}  // namespace
}  // namespace colonmap::landmarks
