// The prone flow on shapes with known answers: a rigid translation, a twist of a straight
// tube, and two walls that nearly touch moving apart in opposite directions without crossing.
#include "RealColon/ColonFlow.h"
#include "Surface/SelfIntersection.h"
#include "TestShapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::realcolon {
namespace {

// Frames every 10 mm along z from 0 to L on the z axis.
ColonFlow StraightFrames(double L, double radius) {
  ColonFlow flow;
  for (double s = 0; s <= L + 1e-9; s += 10.0) {
    FlowControl c;
    c.s = s;
    c.centre = Eigen::Vector3d(0, 0, s);
    c.radius = radius;
    c.support = 2.0 * radius + 20.0;
    flow.controls.push_back(c);
  }
  return flow;
}

TEST(ColonFlow, AUniformDisplacementTranslatesEveryPointInReach) {
  ColonFlow flow = StraightFrames(200.0, 15.0);
  for (FlowControl& c : flow.controls) c.displacement = Eigen::Vector3d(3.0, -20.0, 7.5);
  const TriangleMesh wall = testing::Cylinder(15.0, 200.0, 32, 40);
  const Eigen::MatrixXd moved = flow.Apply(wall.V);
  const Eigen::MatrixXd expected = wall.V.rowwise() + Eigen::RowVector3d(3.0, -20.0, 7.5);
  EXPECT_LT((moved - expected).rowwise().norm().maxCoeff(), 1e-9);
}

TEST(ColonFlow, AUniformTwistRotatesTheWallAboutTheAxis) {
  ColonFlow flow = StraightFrames(200.0, 15.0);
  const double twist = 0.4;
  for (FlowControl& c : flow.controls) c.twist = twist;
  const TriangleMesh wall = testing::Cylinder(15.0, 200.0, 32, 40);
  const Eigen::MatrixXd moved = flow.Apply(wall.V);
  double worst = 0.0;
  for (Eigen::Index v = 0; v < wall.V.rows(); ++v) {
    if (wall.V(v, 2) < 30.0 || wall.V(v, 2) > 170.0) continue;  // frames end at the tube's ends
    const double a = std::atan2(wall.V(v, 1), wall.V(v, 0)), b = std::atan2(moved(v, 1), moved(v, 0));
    worst = std::max({worst, std::fabs(std::remainder(b - a - twist, 2 * M_PI)), std::fabs(moved(v, 2) - wall.V(v, 2)),
                      std::fabs(moved.row(v).head<2>().norm() - 15.0)});
  }
  EXPECT_LT(worst, 1e-5);
}

TEST(ColonFlow, WallsThatNearlyTouchArePushedTogetherWithoutCrossing) {
  // Two parallel tubes 1 mm apart, each moved 12 mm towards the other: where they meet the
  // velocities blend, and the walls close in without ever crossing.
  ColonFlow flow;
  for (int t = 0; t < 2; ++t)
    for (double s = 0; s <= 120.0 + 1e-9; s += 10.0) {
      FlowControl c;
      c.s = s;
      c.centre = Eigen::Vector3d(t == 0 ? 0.0 : 21.0, 0, s);
      c.radius = 10.0;
      c.support = 40.0;
      c.displacement = Eigen::Vector3d(t == 0 ? 12.0 : -12.0, 0, 0);
      flow.controls.push_back(c);
    }
  TriangleMesh both;
  const TriangleMesh a = testing::Cylinder(10.0, 120.0, 48, 60);
  both.V.resize(2 * a.V.rows(), 3);
  both.V.topRows(a.V.rows()) = a.V;
  both.V.bottomRows(a.V.rows()) = a.V.rowwise() + Eigen::RowVector3d(21.0, 0, 0);
  both.F.resize(2 * a.F.rows(), 3);
  both.F.topRows(a.F.rows()) = a.F;
  both.F.bottomRows(a.F.rows()) = a.F.array() + static_cast<int>(a.V.rows());
  ASSERT_EQ(surface::FindSelfIntersections(both.V, both.F).pairs, 0);
  const Eigen::MatrixXd moved = flow.Apply(both.V);
  EXPECT_EQ(surface::FindSelfIntersections(moved, both.F).pairs, 0);
  // Where they touch, the walls stay apart (the facing generatrices, mid-length).
  double gap = 1e9;
  for (Eigen::Index v = 0; v < a.V.rows(); ++v)
    if (std::fabs(a.V(v, 1)) < 1e-9 && a.V(v, 0) > 0 && std::fabs(a.V(v, 2) - 60.0) < 1.5)
      for (Eigen::Index w = 0; w < a.V.rows(); ++w)
        if (std::fabs(a.V(w, 1)) < 1e-9 && a.V(w, 0) < 0 && std::fabs(a.V(w, 2) - 60.0) < 1.5)
          gap = std::min(gap, moved(a.V.rows() + w, 0) - moved(v, 0));
  EXPECT_GT(gap, 0.0);
  EXPECT_LT(gap, 1.0);  // pushed together they do not open up either
}

}  // namespace
}  // namespace colonmap::realcolon
