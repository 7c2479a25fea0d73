// Unit tests of the distortion summaries, textures and morph frames (issue 8), known answers.
#include "Views/DistortionStatistics.h"
#include "Views/DistortionTextures.h"
#include "Views/FlatSegmentMesh.h"
#include "Views/MorphSequence.h"

#include "Core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace {

using namespace colonmap;
using namespace colonmap::views;

TEST(DistortionStatistics, KnownValues) {
  Eigen::VectorXd K(201);
  for (int k = 0; k <= 200; ++k) K(k) = 1.0 + 0.01 * k;  // 1 .. 3, mean 2
  K(100) = std::numeric_limits<double>::infinity();       // a folded face: counted apart
  const DilatationSummary s = SummarizeDilatation(K);
  EXPECT_EQ(s.faces, 200);
  EXPECT_EQ(s.infinite, 1);
  EXPECT_NEAR(s.mean, 2.0, 1e-12);  // symmetric around the removed middle value
  EXPECT_NEAR(s.max, 3.0, 1e-12);
  // rank round(0.99 * 199) = 197 of the 200 sorted finite values; k = 100 is missing, so k = 198.
  EXPECT_NEAR(s.p99, 1.0 + 0.01 * 198, 1e-12);
  Eigen::VectorXd arg(3);
  arg << 3.14159265358979, -1.0, 0.5;
  const Eigen::VectorXd theta = DistortionAngle(arg);
  EXPECT_NEAR(theta(0), 3.14159265358979 / 2, 1e-12);
  EXPECT_NEAR(theta(1), -0.5, 1e-12);
}

TEST(DistortionTextures, CheckerboardAndCircles) {
  Eigen::MatrixXd uv(6, 2);
  // width 1, 8 cells: cell 0.125.
  uv << 0.01, 0.01,    // cell (0, 0): 0
      0.13, 0.01,      // (1, 0): 1
      0.13, 0.13,      // (1, 1): 0
      1.01, 0.01,      // u wraps to (0, 0): 0
      0.0625, 0.0625,  // a cell centre
      std::nan(""), 0.0;
  const Eigen::VectorXd c = CheckerboardAt(uv, 1.0);
  EXPECT_EQ(c(0), 0);
  EXPECT_EQ(c(1), 1);
  EXPECT_EQ(c(2), 0);
  EXPECT_EQ(c(3), 0);
  EXPECT_TRUE(std::isnan(c(5)));
  const Eigen::VectorXd o = CirclesAt(uv, 1.0);
  EXPECT_EQ(o(4), 1);  // centre of a cell: inside its circle
  EXPECT_EQ(o(0), 0);  // a cell corner: outside (0.35 cell radius)
  // Area fraction of the circles: pi 0.35^2 of each cell, measured on a fine grid.
  const int n = 400;
  Eigen::MatrixXd g(n * n, 2);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) g.row(j * n + i) << (i + 0.5) / n, (j + 0.5) / n;
  EXPECT_NEAR(CirclesAt(g, 1.0).mean(), 3.14159265 * 0.35 * 0.35, 0.01);
  EXPECT_NEAR(CheckerboardAt(g, 1.0).mean(), 0.5, 1e-9);
  EXPECT_THROW(CheckerboardAt(uv, 0.0), Error);
}

TEST(MorphSequence, FramesInterpolateFromSupineToProne) {
  const std::vector<double> t = MorphTimes(5);
  ASSERT_EQ(t.size(), 5u);
  EXPECT_EQ(t.front(), 0.0);
  EXPECT_EQ(t.back(), 1.0);
  EXPECT_DOUBLE_EQ(t[2], 0.5);
  Eigen::MatrixXd s = Eigen::MatrixXd::Random(7, 3), p = Eigen::MatrixXd::Random(7, 3);
  EXPECT_EQ(MorphFrame(s, p, 0.0), s);
  EXPECT_EQ(MorphFrame(s, p, 1.0), p);
  EXPECT_LT((MorphFrame(s, p, 0.5) - 0.5 * (s + p)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_THROW(MorphTimes(0), Error);
  EXPECT_THROW(MorphFrame(s, Eigen::MatrixXd::Zero(6, 3), 0.5), Error);
}

TEST(FlatSegmentMesh, ExtractsOneSegment) {
  TriangleMesh m;
  m.V = Eigen::MatrixXd::Zero(7, 3);
  m.F.resize(3, 3);
  m.F << 0, 1, 2, 3, 4, 5, 4, 6, 5;
  Eigen::VectorXd id(7);
  id << 0, 0, 0, 1, 1, 1, 1;
  m.pointData["SegmentId"] = DataArray{id, true};
  const FlatSegmentMesh s = ExtractSegment(m, 1, "mesh");
  EXPECT_EQ(s.vertices.size(), 4);
  EXPECT_EQ(s.vertices(0), 3);
  ASSERT_EQ(s.faces.size(), 2);
  EXPECT_EQ(s.faces(0), 1);
  EXPECT_EQ(s.F.row(1), Eigen::RowVector3i(1, 3, 2));
  Eigen::MatrixXd vals = Eigen::VectorXd::LinSpaced(7, 0, 6);
  EXPECT_EQ(s.PointRows(vals)(3, 0), 6.0);
  m.F(0, 2) = 3;  // a face joining two segments
  EXPECT_THROW(ExtractSegment(m, 0, "mesh"), Error);
  EXPECT_THROW(PointArray(m, "FlatUV", 2, "mesh"), Error);
}

}  // namespace
