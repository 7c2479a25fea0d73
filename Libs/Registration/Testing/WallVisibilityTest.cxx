// Virtual wall on a registration mesh (issue 21): interpolation of the Virtual array and the
// nearest open wall along the colon.
#include "Registration/WallVisibility.h"

#include <gtest/gtest.h>

using namespace colonmap;
using namespace colonmap::registration;

namespace {
// A strip along x: vertices (x, 0, 0) and (x, 1, 0) for x = 0..length, arc length x; Virtual on
// x in [4, 6].
TriangleMesh Strip(bool withVirtual, int length = 10) {
  TriangleMesh m;
  m.V.resize(2 * (length + 1), 3);
  Eigen::MatrixXd arc(2 * (length + 1), 1), virt(2 * (length + 1), 1);
  for (int x = 0; x <= length; ++x) {
    m.V.row(2 * x) << x, 0, 0;
    m.V.row(2 * x + 1) << x, 1, 0;
    arc(2 * x) = arc(2 * x + 1) = x;
    virt(2 * x) = virt(2 * x + 1) = (x >= 4 && x <= 6) ? 1.0 : 0.0;
  }
  m.F.resize(2 * length, 3);
  for (int x = 0; x < length; ++x) {
    m.F.row(2 * x) << 2 * x, 2 * x + 2, 2 * x + 1;
    m.F.row(2 * x + 1) << 2 * x + 1, 2 * x + 2, 2 * x + 3;
  }
  m.pointData["CenterlineArcLength"] = DataArray{arc, false};
  if (withVirtual) m.pointData["Virtual"] = DataArray{virt, true};
  return m;
}
}  // namespace

TEST(WallVisibility, VirtualInterpolatedAndNearestOpenAlongTheColon) {
  const TriangleMesh m = Strip(true);
  const WallVisibility w(m);
  ASSERT_TRUE(w.HasVirtualWall());
  // Face 8: vertices at x = 4, 5 (virtual); face 2: x = 1, 2 (open); face 6: x = 3, 4 (half).
  EXPECT_DOUBLE_EQ(w.VirtualAt(8, Eigen::Vector3d(1, 0, 0) / 1.0), 1.0);
  EXPECT_DOUBLE_EQ(w.VirtualAt(2, Eigen::Vector3d(1.0 / 3, 1.0 / 3, 1.0 / 3)), 0.0);
  EXPECT_NEAR(w.VirtualAt(6, Eigen::Vector3d(0.5, 0.5, 0.0)), 0.5, 1e-12);  // between x = 3 and x = 4
  // A point at x = 4.5 (face 8, between vertices 8 (x=4) and 10 (x=5)): the nearest open wall
  // along the colon is x = 3, 1.5 mm away.
  const OpenPlace o = w.NearestOpen(8, Eigen::Vector3d(0.5, 0.5, 0.0));
  ASSERT_GE(o.vertex, 0);
  EXPECT_DOUBLE_EQ(m.V(o.vertex, 0), 3.0);
  EXPECT_NEAR(o.alongColonMm, 1.5, 1e-12);
}

TEST(WallVisibility, WithoutTheArrayEverythingIsOpen) {
  const TriangleMesh m = Strip(false);
  const WallVisibility w(m);
  EXPECT_FALSE(w.HasVirtualWall());
  EXPECT_EQ(w.VirtualAt(8, Eigen::Vector3d(1, 0, 0)), 0.0);
}

// A point inside a collapsed stretch beside a piece's closed end: off the open wall by more than
// 3 mm, in tissue, with virtual wall about as near. A point on the wall, or far from any virtual
// wall, is not.
TEST(WallVisibility, OffTheSeenWallBesideVirtualWallIsInTheCollapse) {
  const TriangleMesh m = Strip(true, 40);
  const WallVisibility w(m);
  // 4 mm above x = 1: virtual wall (x = 4) 5 mm away.
  EXPECT_NEAR(w.DistanceToVirtual(Eigen::Vector3d(1, 0, 4)), 5.0, 1e-12);
  EXPECT_TRUE(w.OffSeenWall(Eigen::Vector3d(1, 0, 4), 4.0));
  // On the wall (0.5 mm off): seen, whatever is near.
  EXPECT_FALSE(w.OffSeenWall(Eigen::Vector3d(1, 0, 0.5), 0.5));
  // 4 mm above x = 30: the nearest virtual wall is 24 mm along, farther than 4 + 15 mm.
  EXPECT_FALSE(w.OffSeenWall(Eigen::Vector3d(30, 0, 4), 4.0));
  // Without the array there is no collapse to be in.
  const TriangleMesh open = Strip(false, 40);
  EXPECT_FALSE(WallVisibility(open).OffSeenWall(Eigen::Vector3d(1, 0, 4), 4.0));
}
