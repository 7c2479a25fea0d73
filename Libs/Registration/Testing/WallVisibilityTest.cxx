// Virtual wall on a registration mesh (issue 21): interpolation of the Virtual array and the
// nearest open wall along the colon.
#include "Registration/WallVisibility.h"

#include <gtest/gtest.h>

using namespace colonmap;
using namespace colonmap::registration;

namespace {
// A strip along x: vertices (x, 0, 0) and (x, 1, 0) for x = 0..10, arc length x; Virtual on
// x in [4, 6].
TriangleMesh Strip(bool withVirtual) {
  TriangleMesh m;
  m.V.resize(22, 3);
  Eigen::MatrixXd arc(22, 1), virt(22, 1);
  for (int x = 0; x <= 10; ++x) {
    m.V.row(2 * x) << x, 0, 0;
    m.V.row(2 * x + 1) << x, 1, 0;
    arc(2 * x) = arc(2 * x + 1) = x;
    virt(2 * x) = virt(2 * x + 1) = (x >= 4 && x <= 6) ? 1.0 : 0.0;
  }
  m.F.resize(20, 3);
  for (int x = 0; x < 10; ++x) {
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
