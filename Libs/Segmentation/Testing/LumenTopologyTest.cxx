// A mask from any tool made one topological ball (LumenTopology.h), on shapes with known answers.
#include "Core/Error.h"
#include "Segmentation/EulerCharacteristic.h"
#include "Segmentation/LumenTopology.h"
#include "Segmentation/WellComposed.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace colonmap::segmentation {
namespace {

Volume<unsigned char> Grid(std::size_t n) {
  Volume<unsigned char> v;
  v.size = {n, n, n};
  v.spacing = Eigen::Vector3d(1.0, 1.0, 1.0);
  v.Allocate(0);
  return v;
}

template <typename Inside>
void Paint(Volume<unsigned char>& v, Inside inside) {
  for (std::size_t k = 0; k < v.size[2]; ++k)
    for (std::size_t j = 0; j < v.size[1]; ++j)
      for (std::size_t i = 0; i < v.size[0]; ++i)
        if (inside(double(i), double(j), double(k))) v.At(i, j, k) = 1;
}

std::size_t Count(const Volume<unsigned char>& v) { return static_cast<std::size_t>(std::count(v.voxels.begin(), v.voxels.end(), 1)); }

TEST(LumenTopology, ASolidTorusIsCutIntoABall) {
  Volume<unsigned char> v = Grid(48);
  Paint(v, [](double x, double y, double z) {
    const double r = std::hypot(x - 24, y - 24) - 14.0;
    return r * r + (z - 24) * (z - 24) < 25.0;
  });
  NullProgress np;
  const LumenTopology t = SimplifyLumenTopology(v, 2, np);
  EXPECT_EQ(t.components, 1);
  EXPECT_EQ(t.handles, 1);
  EXPECT_GT(t.handleVoxelsRemoved, 0u);
  EXPECT_EQ(EulerCharacteristic(t.ball), 1);
  EXPECT_EQ(CriticalCubes(t.ball), 0);
}

TEST(LumenTopology, TheLargestComponentIsKeptAndItsCavityFilled) {
  Volume<unsigned char> v = Grid(48);
  Paint(v, [](double x, double y, double z) {
    const double big = (x - 16) * (x - 16) + (y - 24) * (y - 24) + (z - 24) * (z - 24);
    const double small = (x - 38) * (x - 38) + (y - 24) * (y - 24) + (z - 24) * (z - 24);
    return (big < 100.0 && big > 9.0) || small < 16.0;  // a hollow ball of radius 10, a ball of 4
  });
  Volume<unsigned char> small = Grid(48);
  Paint(small, [](double x, double y, double z) { return (x - 38) * (x - 38) + (y - 24) * (y - 24) + (z - 24) * (z - 24) < 16.0; });
  Volume<unsigned char> cavity = Grid(48);
  Paint(cavity, [](double x, double y, double z) { return (x - 16) * (x - 16) + (y - 24) * (y - 24) + (z - 24) * (z - 24) <= 9.0; });
  NullProgress np;
  const LumenTopology t = SimplifyLumenTopology(v, 3, np);
  EXPECT_EQ(t.components, 2);
  EXPECT_EQ(t.droppedVoxels, Count(small));
  EXPECT_EQ(t.cavityVoxelsFilled, Count(cavity));
  EXPECT_EQ(t.handles, 0);
  EXPECT_EQ(t.handleVoxelsRemoved, 0u);
  EXPECT_EQ(EulerCharacteristic(t.ball), 1);
  // The crop's geometry: voxel (0,0,0) of the ball is input index `first`.
  EXPECT_NEAR(t.ball.origin.x(), double(t.first[0]), 1e-12);
  EXPECT_EQ(t.VoxelsChanged(), t.droppedVoxels + t.cavityVoxelsFilled + std::size_t(t.wellComposedVoxels));
}

TEST(LumenTopology, AnEmptyMaskIsRefused) {
  NullProgress np;
  EXPECT_THROW(SimplifyLumenTopology(Grid(8), 2, np), Error);
}

}  // namespace
}  // namespace colonmap::segmentation
