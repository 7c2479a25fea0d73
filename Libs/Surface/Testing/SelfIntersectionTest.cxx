// Self-intersection of triangle surfaces, on shapes with known answers.
#include "Surface/SelfIntersection.h"
#include "TestShapes.h"

#include <gtest/gtest.h>

namespace colonmap::surface {
namespace {

TEST(SelfIntersection, SegmentThroughTriangleCrossesAndGrazingDoesNot) {
  const Eigen::Vector3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_TRUE(SegmentCrossesTriangle({0.5, 0.5, -1}, {0.5, 0.5, 1}, a, b, c));
  EXPECT_FALSE(SegmentCrossesTriangle({1.5, 1.5, -1}, {1.5, 1.5, 1}, a, b, c));   // beside the triangle
  EXPECT_FALSE(SegmentCrossesTriangle({0.5, 0.5, 0.1}, {0.5, 0.5, 1}, a, b, c));  // stops short
  EXPECT_FALSE(SegmentCrossesTriangle({0.5, 0.5, 0.0}, {0.5, 0.5, 1}, a, b, c));  // touches, does not cross
}

TEST(SelfIntersection, SphereIsEmbeddedAndAPushedVertexMakesItCross) {
  TriangleMesh s = testing::Icosphere(10.0, 3);
  EXPECT_EQ(FindSelfIntersections(s.V, s.F).pairs, 0);
  // Push one vertex through the sphere to the far side: its fan pierces the opposite wall.
  s.V.row(0) = -1.2 * s.V.row(0);
  const SelfIntersections si = FindSelfIntersections(s.V, s.F);
  EXPECT_GT(si.pairs, 0);
  EXPECT_FALSE(si.examples.empty());
  EXPECT_EQ(SelfIntersectingFaces(s.V, s.F).size(), si.faces.size());
}

TEST(SelfIntersection, TwoSpheresOverlappingCrossAndApartDoNot) {
  const TriangleMesh a = testing::Icosphere(5.0, 2);
  for (const double gap : {2.0, -2.0}) {
    TriangleMesh both;
    both.V.resize(2 * a.V.rows(), 3);
    both.F.resize(2 * a.F.rows(), 3);
    both.V.topRows(a.V.rows()) = a.V;
    both.V.bottomRows(a.V.rows()) = a.V.rowwise() + Eigen::RowVector3d(10.0 + gap, 0, 0);
    both.F.topRows(a.F.rows()) = a.F;
    both.F.bottomRows(a.F.rows()) = a.F.array() + static_cast<int>(a.V.rows());
    EXPECT_EQ(FindSelfIntersections(both.V, both.F).pairs > 0, gap < 0) << "gap " << gap;
  }
}

TEST(SelfIntersection, FacesSharingOneVertexCrossWhenOnePassesThroughTheOther) {
  // Two triangles with the common vertex 0; the second's far edge passes through the first.
  Eigen::MatrixXd V(5, 3);
  V << 0, 0, 0, 2, -1, 0, 2, 1, 0, 1, 0, -1, 1.5, 0, 1;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 3, 4;
  EXPECT_EQ(FindSelfIntersections(V, F).pairs, 1);
  V.row(4) << 1.5, 0, -0.5;  // now wholly below the first triangle's plane
  EXPECT_EQ(FindSelfIntersections(V, F).pairs, 0);
}

}  // namespace
}  // namespace colonmap::surface
