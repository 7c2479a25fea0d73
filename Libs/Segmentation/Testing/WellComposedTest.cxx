// Making voxel sets well-composed without changing their topology (WellComposed.h).
#include "Phantom/Random.h"
#include "Segmentation/EulerCharacteristic.h"
#include "Segmentation/TopologyPreservingGrowth.h"
#include "Segmentation/WellComposed.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace colonmap::segmentation {
namespace {

Volume<unsigned char> Empty(std::size_t n) {
  Volume<unsigned char> v;
  v.size = {n, n, n};
  v.Allocate(0);
  return v;
}

TEST(WellComposed, DiagonalPairsAreResolvedAndTheTopologyKept) {
  // Two solid blocks touching along one edge only (a 2D-diagonal configuration) and a voxel
  // touching a block at one corner (a 3D-diagonal one): connected in 26-connectivity.
  Volume<unsigned char> v = Empty(16);
  for (std::size_t k = 3; k < 9; ++k)
    for (std::size_t j = 3; j < 7; ++j)
      for (std::size_t i = 3; i < 7; ++i) v.At(i, j, k) = 1, v.At(i + 4, j + 4, k) = 1;
  v.At(11, 11, 9) = 1;
  ASSERT_GT(CriticalCubes(v), 0);
  const std::int64_t chi = EulerCharacteristic(v);
  const long changed = MakeWellComposed(v);
  EXPECT_GT(changed, 0);
  EXPECT_EQ(CriticalCubes(v), 0);
  EXPECT_EQ(EulerCharacteristic(v), chi);
}

TEST(WellComposed, RoughTopologicalBallsBecomeWellComposedBalls) {
  // The segmentation's case: a ball grown by simple points inside a rough domain (thresholded
  // noise: many diagonal contacts, and handles the growth refuses to close).
  for (std::uint64_t seed = 1; seed <= 4; ++seed) {
    Volume<unsigned char> domain = Empty(40);
    Volume<float> priority = domain.Like<float>(0.0f);
    const double kx = 0.35 + 0.05 * seed, ky = 0.41, kz = 0.29 + 0.03 * seed;
    for (std::size_t k = 2; k + 2 < 40; ++k)
      for (std::size_t j = 2; j + 2 < 40; ++j)
        for (std::size_t i = 2; i + 2 < 40; ++i) {
          const double f = std::sin(kx * i) * std::cos(ky * j) + std::sin(kz * k + ky * i) +
                           0.4 * phantom::HashToUnit(phantom::Hash(seed, domain.Offset(i, j, k)));
          domain.At(i, j, k) = f > 0.3 ? 1 : 0;
          priority.At(i, j, k) = static_cast<float>(f);
        }
    std::size_t start = 0;
    for (std::size_t v = 0; v < domain.voxels.size(); ++v)
      if (domain.voxels[v] && priority.voxels[v] > priority.voxels[start]) start = v;
    NullProgress np;
    Volume<unsigned char> ball = GrowTopologicalBall(domain, priority, start, np);
    ASSERT_EQ(EulerCharacteristic(ball), 1);
    ASSERT_GT(CriticalCubes(ball), 50) << "seed " << seed;
    MakeWellComposed(ball);
    EXPECT_EQ(CriticalCubes(ball), 0) << "seed " << seed;
    EXPECT_EQ(EulerCharacteristic(ball), 1) << "seed " << seed;
  }
}

TEST(WellComposed, RepairAndEulerCountPollTheHostAndGiveTheSameAnswer) {
  // Rough noise, as above: many passes. With a sink the answer is the same, the fractions rise
  // to 1, and a host that cancels stops both.
  Volume<unsigned char> plain = Empty(40);
  for (std::size_t k = 2; k < 38; ++k)
    for (std::size_t j = 2; j < 38; ++j)
      for (std::size_t i = 2; i < 38; ++i)
        plain.At(i, j, k) = phantom::HashToUnit(phantom::Hash(11, plain.Offset(i, j, k))) < 0.55 ? 1 : 0;
  Volume<unsigned char> polled = plain;
  struct Recording : ProgressSink {
    std::vector<double> fractions;
    bool cancel = false;
    void Report(double f) override {
      fractions.push_back(f);
      if (cancel) throw Cancelled();
    }
  } sink;
  EXPECT_EQ(EulerCharacteristic(polled, &sink), EulerCharacteristic(plain));
  ASSERT_GE(sink.fractions.size(), 5u);
  EXPECT_EQ(sink.fractions.back(), 1.0);
  sink.fractions.clear();
  long forcedPlain = 0, forcedPolled = 0;
  const long changed = MakeWellComposedForcing(plain, &forcedPlain);
  EXPECT_EQ(MakeWellComposedForcing(polled, &forcedPolled, &sink), changed);
  EXPECT_EQ(polled.voxels, plain.voxels);
  EXPECT_EQ(forcedPolled, forcedPlain);
  ASSERT_GE(sink.fractions.size(), 5u);
  EXPECT_TRUE(std::is_sorted(sink.fractions.begin(), sink.fractions.end()));
  EXPECT_EQ(sink.fractions.back(), 1.0);
  sink.cancel = true;
  EXPECT_THROW(EulerCharacteristic(polled, &sink), Cancelled);
  EXPECT_THROW(MakeWellComposedForcing(polled, &forcedPolled, &sink), Cancelled);
}

}  // namespace
}  // namespace colonmap::segmentation
