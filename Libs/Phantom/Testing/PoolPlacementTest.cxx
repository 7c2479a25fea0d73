// Where the phantoms put their fluid pools (PoolPlacement), on floor profiles with known lows.
#include "Phantom/PoolPlacement.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace colonmap::phantom {
namespace {

// A flat floor at height 0 with Gaussian dips of the given depth at the given samples.
std::vector<double> Floor(int n, const std::vector<std::pair<int, double>>& dips) {
  std::vector<double> h(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i)
    for (const auto& [at, depth] : dips) h[static_cast<std::size_t>(i)] -= depth * std::exp(-0.5 * std::pow((i - at) / 5.0, 2));
  return h;
}

TEST(PoolPlacement, PoolsSitInTheDeepestDipsFirstWithTheirLevelsAboveTheFloor) {
  const std::vector<double> h = Floor(600, {{100, 40.0}, {300, 60.0}, {500, 50.0}});
  Rng rng(7, 1);
  const auto pools = PlacePools(h, 2.0, [](int) { return 40.0; }, 3, rng);
  ASSERT_EQ(pools.size(), 3u);
  EXPECT_EQ(pools[0].deepest, 300);
  EXPECT_EQ(pools[1].deepest, 500);
  EXPECT_EQ(pools[2].deepest, 100);
  for (const PoolPlace& p : pools) {
    // 0.2..0.4 of the 40 mm diameter above the lowest floor point.
    EXPECT_GE(p.level - h[static_cast<std::size_t>(p.deepest)], 8.0 - 1e-9);
    EXPECT_LE(p.level - h[static_cast<std::size_t>(p.deepest)], 16.0 + 1e-9);
    // The range is exactly the contiguous floor below the level.
    EXPECT_LT(h[static_cast<std::size_t>(p.lo)], p.level);
    EXPECT_LT(h[static_cast<std::size_t>(p.hi)], p.level);
    EXPECT_GE(h[static_cast<std::size_t>(p.lo - 1)], p.level);
    EXPECT_GE(h[static_cast<std::size_t>(p.hi + 1)], p.level);
  }
}

TEST(PoolPlacement, PoolsCloserThan150MmAreNotBothKept) {
  // Two dips 40 samples (80 mm) apart: the second is too close to the first.
  const std::vector<double> h = Floor(600, {{200, 30.0}, {240, 25.0}, {450, 20.0}});
  Rng rng(3, 2);
  const auto pools = PlacePools(h, 2.0, [](int) { return 30.0; }, 3, rng);
  ASSERT_EQ(pools.size(), 2u);
  EXPECT_EQ(pools[0].deepest, 200);
  EXPECT_EQ(pools[1].deepest, 450);
}

TEST(PoolPlacement, NoPoolNearTheEnds) {
  const std::vector<double> h = Floor(300, {{5, 30.0}, {295, 30.0}});
  Rng rng(1, 1);
  EXPECT_TRUE(PlacePools(h, 2.0, [](int) { return 30.0; }, 4, rng).empty());
}

}  // namespace
}  // namespace colonmap::phantom
