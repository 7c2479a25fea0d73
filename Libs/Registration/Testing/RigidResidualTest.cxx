// RigidResidualRms (RigidResidual.h) on known answers: a rigid motion leaves nothing; a stretch
// along one axis leaves (stretch - 1) x the spread of the points along it.
#include "Registration/RigidResidual.h"

#include "Core/Error.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>

using colonmap::registration::RigidResidualRms;

namespace {

// 11 points on the x axis at -50..50 mm and a ring of 8 around it at radius 10 (not collinear, so
// the rigid fit is unique).
Eigen::MatrixXd Points() {
  Eigen::MatrixXd P(19, 3);
  for (int i = 0; i <= 10; ++i) P.row(i) << -50.0 + 10.0 * i, 0.0, 0.0;
  for (int k = 0; k < 8; ++k) P.row(11 + k) << 0.0, 10.0 * std::cos(k * M_PI / 4), 10.0 * std::sin(k * M_PI / 4);
  return P;
}

}  // namespace

TEST(RigidResidual, ARigidMotionLeavesNothing) {
  const Eigen::MatrixXd P = Points();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Eigen::MatrixXd Q = (P * R.transpose()).rowwise() + Eigen::RowVector3d(30, -20, 5);
  EXPECT_LT(RigidResidualRms(P, Q), 1e-9);
}

TEST(RigidResidual, AStretchAlongAnAxisLeavesItsExcessTimesTheSpread) {
  // x scaled by 1.2 about the centroid (x = 0): every point moves by 0.2 x; the best rigid fit is
  // the identity (symmetric points), so the RMS is 0.2 x the RMS of x over all 19 points.
  const Eigen::MatrixXd P = Points();
  Eigen::MatrixXd Q = P;
  Q.col(0) *= 1.2;
  const double rmsX = std::sqrt(P.col(0).squaredNorm() / 19.0);
  EXPECT_NEAR(RigidResidualRms(P, Q), 0.2 * rmsX, 1e-9);
  // A rigid motion on top changes nothing.
  const Eigen::Matrix3d R = Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_NEAR(RigidResidualRms(P, (Q * R.transpose()).rowwise() + Eigen::RowVector3d(1, 2, 3)), 0.2 * rmsX, 1e-9);
}

TEST(RigidResidual, RefusesArraysThatDoNotPair) {
  EXPECT_THROW(RigidResidualRms(Eigen::MatrixXd::Zero(5, 3), Eigen::MatrixXd::Zero(4, 3)), colonmap::Error);
  EXPECT_THROW(RigidResidualRms(Eigen::MatrixXd::Zero(5, 2), Eigen::MatrixXd::Zero(5, 2)), colonmap::Error);
  EXPECT_EQ(RigidResidualRms(Eigen::MatrixXd::Zero(2, 3), Eigen::MatrixXd::Ones(2, 3)), 0.0);
}
