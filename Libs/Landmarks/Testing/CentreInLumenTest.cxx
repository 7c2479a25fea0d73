// CentreInLumen on a known tube: a closed section of a torus (axis a circle of radius 80 mm in
// the plane z = 0, tube radius 20 mm, 60 degrees, flat caps). The first curve is the straight
// chord between the two cap centres, which cuts the bend by 10.7 mm; centred, every sample must
// lie on the axis circle.
#include "Landmarks/CentreInLumen.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::landmarks {
namespace {

constexpr double kR = 80.0, kTube = 20.0, kAngle = M_PI / 3;

// Rings of the tube (outward normals; CentreInLumen accepts either orientation) and two caps.
void BentTube(Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  const int rings = 121, around = 96;
  V.resize(rings * around + 2, 3);
  for (int i = 0; i < rings; ++i) {
    const double a = kAngle * i / (rings - 1);
    const Eigen::Vector3d c(kR * std::cos(a), kR * std::sin(a), 0), radial(std::cos(a), std::sin(a), 0), z(0, 0, 1);
    for (int j = 0; j < around; ++j) {
      const double t = 2 * M_PI * j / around;
      V.row(i * around + j) = (c + kTube * (std::cos(t) * radial + std::sin(t) * z)).transpose();
    }
  }
  const int c0 = rings * around, c1 = c0 + 1;
  V.row(c0) << kR, 0, 0;
  V.row(c1) << kR * std::cos(kAngle), kR * std::sin(kAngle), 0;
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const int a = i * around + j, b = i * around + (j + 1) % around, c = a + around, d = b + around;
      f.emplace_back(a, b, d);
      f.emplace_back(a, d, c);
    }
  for (int j = 0; j < around; ++j) {
    f.emplace_back(c0, (j + 1) % around, j);
    f.emplace_back(c1, (rings - 1) * around + j, (rings - 1) * around + (j + 1) % around);
  }
  F.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t k = 0; k < f.size(); ++k) F.row(static_cast<Eigen::Index>(k)) = f[k].transpose();
}

// Distance of p from the axis circle.
double OffAxis(const Eigen::Vector3d& p) { return std::hypot(std::hypot(p.x(), p.y()) - kR, p.z()); }

TEST(CentreInLumen, MovesAChordThatCutsABendOntoTheTubeAxis) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  BentTube(V, F);
  Eigen::MatrixXd chord(2, 3);
  chord.row(0) = V.row(V.rows() - 2);
  chord.row(1) = V.row(V.rows() - 1);
  NullProgress none;
  const CentringResult r = CentreInLumen(V, F, chord, CentringOptions(), none);
  double before = 0;
  for (int i = 0; i <= 10; ++i) before = std::max(before, OffAxis((chord.row(0) + i / 10.0 * (chord.row(1) - chord.row(0))).transpose()));
  EXPECT_GT(before, 10.0);
  // Within a tube radius of a cap the nearest wall is the cap, which the normal-plane motion
  // cannot climb away from; those samples start (and stay) near the axis anyway.
  double worst = 0, worstNearCaps = 0;
  for (Eigen::Index i = 0; i < r.points.rows(); ++i) {
    const double fromEnds = std::min((r.points.row(i) - chord.row(0)).norm(), (r.points.row(i) - chord.row(1)).norm());
    (fromEnds > kTube ? worst : worstNearCaps) =
        std::max(fromEnds > kTube ? worst : worstNearCaps, OffAxis(r.points.row(i).transpose()));
  }
  std::printf("chord up to %.1f mm off the axis; centred: up to %.2f mm (%.2f near the caps); clearance %.1f -> %.1f mm\n",
              before, worst, worstNearCaps, r.meanClearanceBefore, r.meanClearanceAfter);
  EXPECT_LT(worst, 0.5);
  EXPECT_LT(worstNearCaps, 2.0);
  EXPECT_GT(r.meanClearanceAfter, r.meanClearanceBefore + 3.0);
  EXPECT_EQ(r.outsideAfter, 0);
  EXPECT_EQ((r.points.row(0) - chord.row(0)).norm(), 0.0);  // the ends stay
  EXPECT_NEAR((r.points.row(r.points.rows() - 1) - chord.row(1)).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace colonmap::landmarks
