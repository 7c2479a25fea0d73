// Material coordinates where a nearest-midline projection fails: a hairpin bend tighter than
// the tube radius, and two limbs whose walls nearly touch.
#include "Analysis/MidlineProjection.h"
#include "RealColon/TubeMaterial.h"
#include "TestShapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::realcolon {
namespace {

// A polyline: down limb A from (0,0,top) to the bend, a half circle of radius bendR, limb B
// back up, ending at (xEnd, 0, top).
Eigen::MatrixXd Hairpin(double top, double bendR, double xEnd) {
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i <= 60; ++i) p.emplace_back(0, 0, top - top * i / 60.0);
  for (int i = 1; i <= 36; ++i) {
    const double a = M_PI * i / 36.0;
    p.emplace_back(bendR - bendR * std::cos(a), 0, -bendR * std::sin(a));
  }
  for (int i = 1; i <= 60; ++i) p.emplace_back(2 * bendR + (xEnd - 2 * bendR) * i / 60.0, 0, top * i / 60.0);
  Eigen::MatrixXd P(static_cast<Eigen::Index>(p.size()), 3);
  for (std::size_t i = 0; i < p.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = p[i].transpose();
  return P;
}

struct Outcome {
  double worstEdgeJump = 0.0;       // largest |s difference| along a mesh edge on the limbs (ours)
  double worstProjectionJump = 0.0; // largest difference of the nearest-midline arc length along any edge
  double limbDeviation = 0.0;       // on the limbs: |s - (arc + offset)|, offset fitted per limb
};

Outcome Check(const Eigen::MatrixXd& P, double radius, double top, double bendR) {
  const TriangleMesh closed = testing::TubeAround(P, radius, 0.75);
  NullProgress np;
  // The tube starts (caecal end) at the end of limb B, the anus is the top of limb A.
  const TubeMaterial m = MakeTubeMaterial(closed, P.row(P.rows() - 1).transpose(), P.row(0).transpose(), {}, np);
  EXPECT_EQ(m.localExtrema, 0);
  EXPECT_EQ(m.maxCurvesPerLevel, 1);
  EXPECT_GT(m.checkedLevels, 100);
  Outcome o;
  const double total = analysis::ArcLength(P)(P.rows() - 1);
  Eigen::VectorXd fromStart(m.tube.V.rows());
  for (Eigen::Index v = 0; v < m.tube.V.rows(); ++v) fromStart(v) = testing::NearestArc(P, m.tube.V.row(v).transpose());
  // On each limb, away from the bend (40 mm) and the ends (30 mm), s follows the caecal-end arc
  // length up to a constant (the centreline cuts the bend's corner). (At the bend and the ends
  // s may change fast across the wall: the inner side of a bend is shorter than its centreline.)
  const double bendStart = top, bendEnd = top + M_PI * bendR;
  const auto onLimb = [&](int v) {
    const double a = fromStart(v);
    return (a > 30.0 && a < bendStart - 40.0) || (a > bendEnd + 40.0 && a < total - 30.0);
  };
  for (Eigen::Index f = 0; f < m.tube.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = m.tube.F(f, k), b = m.tube.F(f, (k + 1) % 3);
      o.worstProjectionJump = std::max(o.worstProjectionJump, std::fabs(fromStart(a) - fromStart(b)));
      if (onLimb(a) && onLimb(b)) o.worstEdgeJump = std::max(o.worstEdgeJump, std::fabs(m.s(a) - m.s(b)));
    }
  for (int limb = 0; limb < 2; ++limb) {
    std::vector<std::pair<double, double>> pts;
    for (Eigen::Index v = 0; v < m.tube.V.rows(); ++v) {
      const double a = fromStart(v);
      const bool onA = a > 30.0 && a < bendStart - 40.0, onB = a > bendEnd + 40.0 && a < total - 30.0;
      if (limb == 0 ? onA : onB) pts.emplace_back(m.s(v), total - a);
    }
    EXPECT_GT(pts.size(), 100u);
    double offset = 0.0;
    for (auto& [s, arc] : pts) offset += s - arc;
    offset /= static_cast<double>(pts.size());
    for (auto& [s, arc] : pts) o.limbDeviation = std::max(o.limbDeviation, std::fabs(s - arc - offset));
  }
  return o;
}

TEST(TubeMaterial, HairpinTighterThanTheRadiusStaysMonotoneWhereTheProjectionJumps) {
  // Bend radius 6 mm, tube radius 10 mm: the limbs fuse around the bend.
  const Eigen::MatrixXd P = Hairpin(150.0, 6.0, 70.0);
  const Outcome o = Check(P, 10.0, 150.0, 6.0);
  EXPECT_GT(o.worstProjectionJump, 15.0);  // the projection jumps across the bend...
  EXPECT_LT(o.worstEdgeJump, 2.0);         // ... s does not (mesh edges are <= ~1 mm)
  EXPECT_LT(o.limbDeviation, 2.5);
}

TEST(TubeMaterial, LimbsWhoseWallsNearlyTouchKeepTheirOwnCoordinate) {
  // Limb axes 21.5 mm apart, radius 10 mm: 1.5 mm between the walls over 150 mm.
  const Eigen::MatrixXd P = Hairpin(150.0, 10.75, 21.5);
  const Outcome o = Check(P, 10.0, 150.0, 10.75);
  EXPECT_LT(o.worstEdgeJump, 2.0);
  EXPECT_LT(o.limbDeviation, 2.5);
}

}  // namespace
}  // namespace colonmap::realcolon
