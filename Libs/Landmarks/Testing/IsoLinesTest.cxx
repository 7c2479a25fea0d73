// Level sets of a linear function on a cylinder: known loops, centroids, radii and cuts.
#include "Landmarks/IsoLines.h"
#include "Surface/MeshTopology.h"
#include "../../RealColon/Testing/TestShapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::landmarks {
namespace {

Eigen::VectorXd Height(const TriangleMesh& m, double h) { return m.V.col(2) / h; }

TEST(IsoLines, LevelSetOfTheAxialCoordinateIsOneLoopOfThePolygonsPerimeter) {
  const int n = 48;
  const TriangleMesh c = realcolon::testing::Cylinder(10.0, 50.0, n, 25);
  const Eigen::VectorXd f = Height(c, 50.0);
  const std::vector<LevelCurve> curves = LevelSet(c.V, c.F, f, 0.37);
  ASSERT_EQ(curves.size(), 1u);
  EXPECT_TRUE(curves[0].closed);
  // The cut of a prism of n sides: the regular polygon's perimeter, exactly.
  EXPECT_NEAR(curves[0].Length(), 2.0 * n * 10.0 * std::sin(M_PI / n), 1e-9);
  for (Eigen::Index i = 0; i < curves[0].points.rows(); ++i) EXPECT_NEAR(curves[0].points(i, 2), 18.5, 1e-9);
}

TEST(IsoLines, SummaryGivesTheAxisTheRadiusAndTheLowestPoint) {
  const TriangleMesh c = realcolon::testing::Cylinder(10.0, 50.0, 64, 25);
  const Eigen::VectorXd f = Height(c, 50.0);
  Eigen::VectorXd levels(3);
  levels << 0.1, 0.5, 0.93;
  const LevelSummary s = SummarizeLevels(c.V, c.F, f, levels, Eigen::Vector3d(0, 1, 0));
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(s.centroid(i, 0), 0.0, 1e-9);
    EXPECT_NEAR(s.centroid(i, 1), 0.0, 1e-9);
    EXPECT_NEAR(s.centroid(i, 2), 50.0 * levels(i), 1e-9);
    EXPECT_NEAR(s.meanRadius(i), 10.0, 0.01);  // the polygon's sides lie inside the circle
    EXPECT_NEAR(s.maxRadius(i), 10.0, 1e-9);
    EXPECT_NEAR(s.lowest(i, 1), 10.0, 1e-9);  // "down" is +y: the vertex at angle pi/2
  }
}

TEST(IsoLines, CutAtLevelMakesTheLevelSetAChainOfEdges) {
  TriangleMesh c = realcolon::testing::Cylinder(10.0, 50.0, 32, 10);
  DataArray tag;
  tag.values = c.V.col(0);
  c.pointData["X"] = tag;
  Eigen::VectorXd f = Height(c, 50.0);
  const Eigen::Index before = c.V.rows();
  const std::vector<int> added = CutAtLevel(c, f, 0.33);
  EXPECT_EQ(added.size(), 64u);  // each of the 32 vertical edges and 32 diagonals between the rings
  ASSERT_EQ(f.size(), c.V.rows());
  EXPECT_EQ(c.V.rows(), before + static_cast<Eigen::Index>(added.size()));
  for (int v : added) {
    EXPECT_DOUBLE_EQ(f(v), 0.33);
    EXPECT_NEAR(c.V(v, 2), 16.5, 1e-9);
    EXPECT_NEAR(c.pointData.at("X").values(v, 0), c.V(v, 0), 1e-9);  // arrays interpolated
  }
  for (Eigen::Index t = 0; t < c.F.rows(); ++t) {  // no face has corners strictly on both sides
    bool below = false, above = false;
    for (int k = 0; k < 3; ++k) below = below || f(c.F(t, k)) < 0.33, above = above || f(c.F(t, k)) > 0.33;
    EXPECT_FALSE(below && above) << "face " << t;
  }
  const surface::TopologyReport r = surface::AnalyzeTopology(c.F);
  EXPECT_EQ(r.euler, 0);
  EXPECT_EQ(r.boundaryLoops, 2);
  EXPECT_EQ(r.inconsistentEdges, 0);
}

}  // namespace
}  // namespace colonmap::landmarks
