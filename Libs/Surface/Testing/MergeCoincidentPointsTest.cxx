// MergeCoincidentPoints (MergeCoincidentPoints.h) on known answers: two pieces sharing a cut
// loop weld into one mesh; the lowest index keeps its place; merging does not chain.
#include "Surface/MergeCoincidentPoints.h"

#include <gtest/gtest.h>

using colonmap::TriangleMesh;
using colonmap::surface::MergeCoincidentPoints;

TEST(MergeCoincidentPoints, TwoPiecesSharingAnEdgeWeldIntoOne) {
  // Triangles (0, 1, 2) and (3, 4, 5); points 3 and 4 repeat 1 and 2 within 0.01 mm, as a piece
  // cut from the same surface does.
  TriangleMesh m;
  m.V.resize(6, 3);
  m.V << 0, 0, 0, 1, 0, 0, 0, 1, 0,  //
      1.01, 0, 0, 0, 1.005, 0, 1, 1, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 2, 3, 5, 4;
  std::vector<int> into;
  const TriangleMesh w = MergeCoincidentPoints(m, 0.05, &into);
  ASSERT_EQ(w.V.rows(), 4);
  EXPECT_EQ(into, (std::vector<int>{0, 1, 2, 1, 2, 3}));
  EXPECT_EQ(w.F.row(1), Eigen::RowVector3i(1, 3, 2));
  EXPECT_EQ(w.V.row(1), m.V.row(1));  // the lower index keeps its coordinates
  EXPECT_EQ(w.V.row(3), m.V.row(5));
}

TEST(MergeCoincidentPoints, MergingDoesNotChainAndCollapsedFacesKeepTheirRepeatedCorner) {
  // 0, 1, 2 on a line 0.04 mm apart, tolerance 0.05: 1 joins 0; 2 is 0.08 from 0 and keeps its
  // place (a merged point takes nobody). Face (0, 1, 3) collapses to (0, 0, 2).
  TriangleMesh m;
  m.V.resize(4, 3);
  m.V << 0, 0, 0, 0.04, 0, 0, 0.08, 0, 0, 0, 5, 0;
  m.F.resize(2, 3);
  m.F << 0, 1, 3, 1, 2, 3;
  const TriangleMesh w = MergeCoincidentPoints(m, 0.05);
  ASSERT_EQ(w.V.rows(), 3);
  EXPECT_EQ(w.F.row(0), Eigen::RowVector3i(0, 0, 2));
  EXPECT_EQ(w.F.row(1), Eigen::RowVector3i(0, 1, 2));
  // Nothing within the tolerance: the mesh comes back as it was.
  const TriangleMesh same = MergeCoincidentPoints(m, 0.01);
  ASSERT_EQ(same.V.rows(), m.V.rows());
  ASSERT_EQ(same.F.rows(), m.F.rows());
  EXPECT_EQ(same.V, m.V);
  EXPECT_EQ(same.F, m.F);
}
