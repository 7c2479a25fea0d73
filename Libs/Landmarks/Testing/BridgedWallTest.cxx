// Wall not seen (bridged collapsed stretches) along the colon, with known answers: a straight
// tube whose along-colon function is z / length and whose wall is virtual over 80 <= z <= 120.
#include "Landmarks/BridgedWall.h"

#include "../../RealColon/Testing/TestShapes.h"

#include <gtest/gtest.h>

namespace colonmap::landmarks {
namespace {

TEST(BridgedWall, PlacesInsideTheBridgedStretchAndOnlyThoseAreFlagged) {
  TriangleMesh c = realcolon::testing::Cylinder(10.0, 200.0, 48, 200);
  const Eigen::VectorXd f = c.V.col(2) / 200.0;
  Eigen::MatrixXd q(6, 3);
  q << 0, 0, 50,  //
      0, 0, 100,  //
      5, 0, 100,  //
      0, 0, 118,  //
      0, 0, 125,  //
      0, 0, 150;
  // Without a Virtual array nothing is bridged.
  for (bool b : OnBridgedWall(c, f, q)) EXPECT_FALSE(b);
  Eigen::MatrixXd marks(c.V.rows(), 1);
  for (Eigen::Index v = 0; v < c.V.rows(); ++v) marks(v, 0) = c.V(v, 2) >= 80.0 && c.V(v, 2) <= 120.0 ? 1.0 : 0.0;
  c.pointData["Virtual"] = DataArray{marks, true};
  const std::vector<bool> got = OnBridgedWall(c, f, q);
  const std::vector<bool> want = {false, true, true, true, false, false};
  ASSERT_EQ(got.size(), want.size());
  for (std::size_t i = 0; i < want.size(); ++i) EXPECT_EQ(got[i], want[i]) << "z " << q(static_cast<Eigen::Index>(i), 2);
}

}  // namespace
}  // namespace colonmap::landmarks
