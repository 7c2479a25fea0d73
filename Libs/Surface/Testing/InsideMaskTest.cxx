// The inside of closed surfaces (InsideMask) and their signed volume (SignedVolume), against
// known answers.
#include "Core/Error.h"
#include "Surface/InsideMask.h"
#include "Surface/SignedVolume.h"
#include "TestShapes.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace colonmap::surface {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(SignedVolume, SphereVolumeWithTheSignOfItsOrientation) {
  const TriangleMesh s = testing::Icosphere(10.0, 5);
  const double v = SignedVolume(s.V, s.F);
  // An inscribed polyhedron: a little less than the ball (level 5: within 0.2%).
  EXPECT_NEAR(std::abs(v), 4.0 / 3.0 * kPi * 1000.0, 0.003 * 4.0 / 3.0 * kPi * 1000.0);
  Eigen::MatrixXi flipped = s.F;
  flipped.col(1).swap(flipped.col(2));
  EXPECT_DOUBLE_EQ(SignedVolume(s.V, flipped), -v);
}

TEST(SignedVolume, UnitTetrahedron) {
  Eigen::MatrixXd V(4, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  Eigen::MatrixXi F(4, 3);
  F << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;  // counter-clockwise seen from outside
  EXPECT_NEAR(SignedVolume(V, F), 1.0 / 6.0, 1e-15);
}

TEST(InsideMask, BallVoxelsAreThoseWithinTheRadius) {
  const double r = 12.0;
  TriangleMesh s = testing::Icosphere(r, 5);
  s.V.rowwise() += Eigen::RowVector3d(3.3, -2.1, 5.7);  // off the grid's symmetry
  Volume<unsigned char> mask;
  mask.size = {{40, 40, 40}};
  mask.spacing = Eigen::Vector3d(0.8, 0.8, 0.8);
  mask.origin = Eigen::Vector3d(3.3 - 15.6, -2.1 - 15.6, 5.7 - 15.6);
  FillInsideMask(s, mask);
  ASSERT_EQ(mask.voxels.size(), mask.NumberOfVoxels());
  long wrong = 0, inside = 0;
  for (std::size_t k = 0; k < 40; ++k)
    for (std::size_t j = 0; j < 40; ++j)
      for (std::size_t i = 0; i < 40; ++i) {
        const Eigen::Vector3d p = mask.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
        const double d = (p - Eigen::Vector3d(3.3, -2.1, 5.7)).norm();
        const bool in = mask.At(i, j, k) == 1;
        inside += in;
        // The polyhedron lies within 0.01 mm inside the sphere at level 5; voxels farther than
        // that from the sphere must be classified as the sphere says.
        if (std::abs(d - r) > 0.05 && in != (d < r)) ++wrong;
      }
  EXPECT_EQ(wrong, 0);
  EXPECT_NEAR(double(inside) * 0.512, 4.0 / 3.0 * kPi * r * r * r, 0.02 * 4.0 / 3.0 * kPi * r * r * r);
}

TEST(InsideMask, RefusesAnObliqueGrid) {
  const TriangleMesh s = testing::Icosphere(5.0, 2);
  Volume<unsigned char> mask;
  mask.size = {{8, 8, 8}};
  mask.direction = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  EXPECT_THROW(FillInsideMask(s, mask), Error);
}

}  // namespace
}  // namespace colonmap::surface
