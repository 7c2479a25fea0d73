// Topology-preserving growth and the ITK filters around it, on shapes of known topology.
// Independent checks: Euler characteristic by V - E + F - C counting and component counts by a
// plain breadth-first search (neither is used by the growth).
#include "SegmentationTestUtils.h"
#include "Core/RecordingProgress.h"
#include "Segmentation/EulerCharacteristic.h"
#include "Segmentation/ItkSegmentationFilters.h"
#include "Segmentation/LabelComponents.h"
#include "Phantom/Random.h"
#include "Segmentation/TopologyPreservingGrowth.h"
#include "Core/Error.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

using namespace colonmap;
using namespace colonmap::segmentation;
using namespace colonmap::segmentation::testing;

namespace {
detail::Grid GridOf(const Volume<unsigned char>& v) {
  detail::Grid g;
  for (int d = 0; d < 3; ++d) {
    g.size[d] = v.size[d];
    g.spacing[d] = v.spacing[d];
  }
  return g;
}
Volume<float> Depth(const Volume<unsigned char>& v) {
  Volume<float> d;
  d.size = v.size;
  NullProgress none;
  detail::InsideDistance(GridOf(v), v.voxels.data(), d.voxels, none);
  return d;
}
std::size_t Deepest(const Volume<float>& d) {
  return std::size_t(std::max_element(d.voxels.begin(), d.voxels.end()) - d.voxels.begin());
}
Volume<unsigned char> Torus() {  // major radius 12, minor radius 4 voxels
  return Shape(36, 36, 14, [](double i, double j, double k) {
    const double r = std::hypot(i - 17.5, j - 17.5);
    return (r - 12) * (r - 12) + (k - 6.5) * (k - 6.5) <= 16;
  });
}
}  // namespace

TEST(TopologyGrowth, SolidTorusBecomesABallCutAtOnePlace) {
  const Volume<unsigned char> torus = Torus();
  ASSERT_EQ(EulerCharacteristic(torus), 0);
  const Volume<float> depth = Depth(torus);
  NullProgress none;
  GrowthStatistics stats;
  const Volume<unsigned char> ball = GrowTopologicalBall(torus, depth, Deepest(depth), none, &stats);
  EXPECT_EQ(EulerCharacteristic(ball), 1);
  EXPECT_EQ(Components(ball, 1), 1);
  EXPECT_EQ(Components(ball, 0), 1);  // no cavity
  EXPECT_EQ(stats.grownVoxels, CountSet(ball));
  EXPECT_EQ(stats.domainVoxels, CountSet(torus));
  for (std::size_t v = 0; v < ball.voxels.size(); ++v) ASSERT_TRUE(!ball.voxels[v] || torus.voxels[v]);
  // The handle is cut by a thin slab: at least one cross-section, at most a few of them
  // (cross-section pi 4^2 ~ 50 voxels; the domain has 2 pi 12 pi 16 ~ 3800).
  EXPECT_GE(stats.refusedVoxels, 20u);
  EXPECT_LE(stats.refusedVoxels, 200u);
}

TEST(TopologyGrowth, BallWithCavityIsFilledThenGrownWhole) {
  const auto ball = [](double i, double j, double k) {
    return (i - 11) * (i - 11) + (j - 11) * (j - 11) + (k - 11) * (k - 11) <= 81;
  };
  const auto cavity = [](double i, double j, double k) {
    return (i - 13) * (i - 13) + (j - 11) * (j - 11) + (k - 11) * (k - 11) <= 6;
  };
  Volume<unsigned char> shell = Shape(23, 23, 23, [&](double i, double j, double k) { return ball(i, j, k) && !cavity(i, j, k); });
  const Volume<unsigned char> full = Shape(23, 23, 23, ball);
  ASSERT_EQ(EulerCharacteristic(shell), 2);
  NullProgress none;
  // Without filling, the growth cannot close the cavity: it leaves a channel open instead.
  {
    const Volume<float> depth = Depth(shell);
    GrowthStatistics stats;
    const Volume<unsigned char> grown = GrowTopologicalBall(shell, depth, Deepest(depth), none, &stats);
    EXPECT_EQ(EulerCharacteristic(grown), 1);
    EXPECT_GT(stats.refusedVoxels, 0u);
  }
  Volume<unsigned char> filled = shell;
  detail::FillCavities6(GridOf(filled), filled.voxels, none);
  EXPECT_EQ(filled.voxels, full.voxels);
  const Volume<float> depth = Depth(filled);
  GrowthStatistics stats;
  const Volume<unsigned char> grown = GrowTopologicalBall(filled, depth, Deepest(depth), none, &stats);
  EXPECT_EQ(grown.voxels, full.voxels);
  EXPECT_EQ(stats.refusedVoxels, 0u);
}

TEST(TopologyGrowth, CavityFillingUsesFaceConnectedBackground) {
  // A pocket that reaches the outside only through an edge is a cavity for (26,6).
  Volume<unsigned char> cube = Shape(9, 9, 9, [](double i, double j, double k) {
    return i >= 1 && j >= 1 && k >= 1 && i <= 7 && j <= 7 && k <= 7;
  });
  cube.At(4, 4, 4) = 0;  // the pocket
  // Open a diagonal channel from the pocket to the outside: voxels that touch only by edges.
  cube.At(5, 5, 4) = 0;
  cube.At(6, 6, 4) = 0;
  cube.At(7, 7, 4) = 0;
  NullProgress none;
  Volume<unsigned char> filled = cube;
  detail::FillCavities6(GridOf(filled), filled.voxels, none);
  EXPECT_EQ(CountSet(filled), 7u * 7u * 7u - 1u);  // all but the face-open corner voxel
  EXPECT_EQ(filled.At(7, 7, 4), 0);
}

TEST(TopologyGrowth, OurComponentLabelsAreItksOnNoiseAndShapes) {
  // Random masks of several densities (many components, diagonal contacts, runs at the grid's
  // faces) on odd grid sizes: the same number of components and the same label at every voxel as
  // itk::ConnectedComponentImageFilter, the reference.
  NullProgress none;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const double density = 0.02 + 0.015 * double(seed);  // below and near 26-percolation (about 0.1)
    Volume<unsigned char> m = Shape(23 + seed, 17 + 2 * seed, 11 + seed, [&](double i, double j, double k) {
      return phantom::HashToUnit(phantom::Hash(seed, std::uint64_t(i + 100 * j + 10000 * k))) < density;
    });
    std::vector<std::uint32_t> ours, itk;
    const std::uint32_t n = detail::LabelComponents26(GridOf(m), m.voxels.data(), ours, none);
    EXPECT_EQ(n, detail::ItkLabelComponents26(GridOf(m), m.voxels.data(), itk, none)) << "seed " << seed;
    EXPECT_EQ(ours, itk) << "seed " << seed;
    EXPECT_GT(n, 1u) << "seed " << seed;
  }
  // One component: its labels only when asked for.
  const Volume<unsigned char> block = Shape(8, 8, 8, [](double i, double j, double k) { return i > 1 && j > 2 && k > 3; });
  std::vector<std::uint32_t> labels{7};
  EXPECT_EQ(detail::LabelComponents26(GridOf(block), block.voxels.data(), labels, none, /*labelsOfOne=*/false), 1u);
  EXPECT_TRUE(labels.empty());
  EXPECT_EQ(detail::LabelComponents26(GridOf(block), block.voxels.data(), labels, none), 1u);
  EXPECT_EQ(labels.size(), block.voxels.size());
  // A host that cancels stops it at its first poll.
  RecordingProgress cancelling(1);
  EXPECT_THROW(detail::LabelComponents26(GridOf(block), block.voxels.data(), labels, cancelling), Cancelled);
}

TEST(TopologyGrowth, OurCavityFillingIsItksOnNoise) {
  // Dense random masks (the background breaks into many pockets, some 6-connected to the border
  // only through narrow paths) on odd grid sizes: every voxel as itk::BinaryFillholeImageFilter
  // (face connectivity), the reference, fills it.
  NullProgress none;
  for (std::uint64_t seed = 1; seed <= 6; ++seed) {
    const double density = 0.55 + 0.05 * double(seed);  // background 0.4 .. 0.15: around 6-percolation (0.31)
    Volume<unsigned char> m = Shape(21 + seed, 15 + 2 * seed, 13 + seed, [&](double i, double j, double k) {
      return phantom::HashToUnit(phantom::Hash(seed + 50, std::uint64_t(i + 100 * j + 10000 * k))) < density;
    });
    Volume<unsigned char> ours = m, itk = m;
    detail::FillCavities6(GridOf(ours), ours.voxels, none);
    detail::ItkFillCavities6(GridOf(itk), itk.voxels, none);
    EXPECT_EQ(ours.voxels, itk.voxels) << "seed " << seed;
    EXPECT_GT(CountSet(ours), CountSet(m)) << "seed " << seed;  // there were cavities to fill
    EXPECT_LT(CountSet(ours), ours.voxels.size()) << "seed " << seed;  // and background that reaches out
  }
  // Thin grids (every voxel on the border), all foreground, all background.
  int k = 0;
  for (const std::array<std::size_t, 3>& size : {std::array<std::size_t, 3>{1, 7, 5}, {6, 2, 4}, {5, 6, 1}, {3, 3, 3}})
    for (double density : {0.0, 0.5, 1.0}) {
      Volume<unsigned char> m = Shape(size[0], size[1], size[2], [&](double i, double j, double l) {
        return phantom::HashToUnit(phantom::Hash(++k, std::uint64_t(i + 100 * j + 10000 * l))) < density;
      });
      Volume<unsigned char> ours = m, itk = m;
      detail::FillCavities6(GridOf(ours), ours.voxels, none);
      detail::ItkFillCavities6(GridOf(itk), itk.voxels, none);
      EXPECT_EQ(ours.voxels, itk.voxels) << size[0] << "x" << size[1] << "x" << size[2] << " density " << density;
      if (std::min({size[0], size[1], size[2]}) <= 2 || density != 0.5)
        EXPECT_EQ(ours.voxels, m.voxels) << "no cavity in a grid this thin or uniform";
    }
}

TEST(TopologyGrowth, ComponentRunsOfACtAreTheLabelsOfItsThresholdedMask) {
  // The segmentation labels a CT's air as runs straight from the HU values: the same components,
  // numbered the same, as the label grid of the thresholded mask.
  NullProgress none;
  Volume<unsigned char> mask = Shape(31, 19, 17, [](double i, double j, double k) {
    return phantom::HashToUnit(phantom::Hash(9, std::uint64_t(i + 100 * j + 10000 * k))) < 0.12;
  });
  std::vector<short> hu(mask.voxels.size());
  for (std::size_t v = 0; v < hu.size(); ++v) hu[v] = mask.voxels[v] ? short(-1000 + int(v % 500)) : short(40 - int(v % 300));
  const detail::ComponentRuns runs = detail::LabelComponentRunsBelow26(GridOf(mask), hu.data(), -480, none);
  std::vector<std::uint32_t> labels;
  ASSERT_EQ(runs.count, detail::LabelComponents26(GridOf(mask), mask.voxels.data(), labels, none));
  std::vector<std::uint32_t> painted(labels.size(), 0);
  ASSERT_EQ(runs.rowStart.size(), mask.size[1] * mask.size[2] + 1);
  for (std::size_t row = 0; row + 1 < runs.rowStart.size(); ++row)
    for (std::size_t r = runs.rowStart[row]; r < runs.rowStart[row + 1]; ++r)
      for (std::uint32_t i = runs.runs[r].first; i <= runs.runs[r].last; ++i) painted[row * mask.size[0] + i] = runs.runs[r].label;
  EXPECT_EQ(painted, labels);
  EXPECT_GT(runs.count, 10u);
}

TEST(TopologyGrowth, ItkFiltersOnKnownShapes) {
  NullProgress none;
  // Components: two blobs touching at a vertex are one (26-connectivity), a third apart.
  Volume<unsigned char> m = Shape(10, 10, 10, [](double i, double j, double k) {
    return (i == 2 && j == 2 && k == 2) || (i == 3 && j == 3 && k == 3) || (i >= 6 && j >= 6 && k >= 6 && i < 9 && j < 9 && k < 9);
  });
  std::vector<std::uint32_t> labels;
  EXPECT_EQ(detail::LabelComponents26(GridOf(m), m.voxels.data(), labels, none), 2u);
  EXPECT_EQ(labels[m.Offset(2, 2, 2)], labels[m.Offset(3, 3, 3)]);
  EXPECT_NE(labels[m.Offset(2, 2, 2)], labels[m.Offset(7, 7, 7)]);
  EXPECT_EQ(labels[0], 0u);
  // Depth in mm honours spacing: a slab 9 voxels thick along k at 2 mm: centre 8 mm from the
  // boundary-layer centres.
  Volume<unsigned char> slab = Shape(12, 12, 13, [](double i, double j, double k) {
    return i >= 1 && i <= 10 && j >= 1 && j <= 10 && k >= 2 && k <= 10;
  });
  slab.spacing = Eigen::Vector3d(10.0, 10.0, 2.0);
  const Volume<float> depth = Depth(slab);
  EXPECT_NEAR(depth.At(5, 5, 6), 8.0, 1e-4);
  EXPECT_NEAR(depth.At(5, 5, 2), 0.0, 1e-4);
  EXPECT_EQ(depth.At(0, 0, 0), 0.0f);
}

TEST(TopologyGrowth, ReportsProgressAndCancels) {
  const Volume<unsigned char> torus = Shape(70, 70, 40, [](double i, double j, double k) {
    const double r = std::hypot(i - 34.5, j - 34.5);
    return (r - 20) * (r - 20) + (k - 19.5) * (k - 19.5) <= 144;
  });
  const Volume<float> depth = Depth(torus);
  struct Counting : ProgressSink {
    int calls = 0, cancelAt = -1;
    void Report(double) override {
      if (++calls == cancelAt) throw Cancelled();
    }
  } progress;
  GrowTopologicalBall(torus, depth, Deepest(depth), progress);
  EXPECT_GE(progress.calls, 3);
  Counting cancelling;
  cancelling.cancelAt = 2;
  EXPECT_THROW(GrowTopologicalBall(torus, depth, Deepest(depth), cancelling), Cancelled);
  // A domain on the grid border is refused (neighbourhoods would leave the grid).
  const Volume<unsigned char> full = Shape(4, 4, 4, [](double, double, double) { return true; });
  NullProgress none;
  EXPECT_THROW(GrowTopologicalBall(full, Depth(full), 0, none), Error);
}
