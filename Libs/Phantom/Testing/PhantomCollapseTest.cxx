// Collapsed stretches of the phantom (issue 21): where they are drawn, that the rest of the
// anatomy does not change, that the CT has wall instead of lumen there (and only there), and
// that the truth says which wall points are collapsed in which scan.
#include "Phantom/Collapse.h"
#include "Phantom/Phantom.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace colonmap;
using namespace colonmap::phantom;

namespace {
PhantomOptions Coarse(std::uint32_t seed, int collapses) {
  PhantomOptions o;
  o.seed = seed;
  o.collapses = collapses;
  o.fluid = false;
  o.spacing = Eigen::Vector3d(2.5, 2.5, 2.5);
  return o;
}
}  // namespace

TEST(PhantomCollapse, StretchesAreDrawnWhereTheIssueSaysAndNothingElseMoves) {
  int perScan[3] = {0, 0, 0};  // supine only, prone only, both
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    const ColonAnatomy plain = MakeAnatomy(Coarse(seed, 0));
    const ColonAnatomy a = MakeAnatomy(Coarse(seed, 2));
    ASSERT_TRUE(plain.collapses.empty());
    ASSERT_EQ(a.collapses.size(), 2u) << "seed " << seed;
    for (std::size_t k = 0; k < a.collapses.size(); ++k) {
      const CollapsedStretch& c = a.collapses[k];
      EXPECT_GE(c.s1 - c.s0, 20.0);
      EXPECT_LE(c.s1 - c.s0, 80.0);
      EXPECT_GE(c.s0, 60.0);
      EXPECT_LE(c.s1, a.length - 60.0);
      EXPECT_TRUE(c.supine || c.prone);
      EXPECT_EQ(c.segment, a.SegmentOf(0.5 * (c.s0 + c.s1)));
      if (k > 0) {
        EXPECT_GT(c.s0, a.collapses[k - 1].s1 + 60.0);
      }
      ++perScan[c.supine && c.prone ? 2 : (c.supine ? 0 : 1)];
    }
    // The collapses have a stream of their own: the anatomy is otherwise the same.
    EXPECT_EQ(a.length, plain.length);
    ASSERT_EQ(a.folds.size(), plain.folds.size());
    for (std::size_t f = 0; f < a.folds.size(); ++f) EXPECT_EQ(a.folds[f].s, plain.folds[f].s);
    ASSERT_EQ(a.polyps.size(), plain.polyps.size());
    for (std::size_t p = 0; p < a.polyps.size(); ++p) EXPECT_EQ(a.polyps[p].theta, plain.polyps[p].theta);
    // Same seed, same draw.
    EXPECT_EQ(MakeAnatomy(Coarse(seed, 2)).collapses[1].s0, a.collapses[1].s0);
  }
  // 40 stretches: each kind of scan choice occurs.
  EXPECT_GT(perScan[0], 0);
  EXPECT_GT(perScan[1], 0);
  EXPECT_GT(perScan[2], 0);
  EXPECT_THROW(DrawCollapses(MakeAnatomy(Coarse(1, 0)), 5, 1), std::invalid_argument);
}

TEST(PhantomCollapse, CTHasWallInsteadOfLumenOnlyInTheCollapsedStretch) {
  NullProgress none;
  const PhantomOptions with = Coarse(3, 1), without = Coarse(3, 0);
  const ColonAnatomy a = MakeAnatomy(with);
  ASSERT_EQ(a.collapses.size(), 1u);
  const CollapsedStretch& c = a.collapses[0];
  for (const Posture posture : {Posture::Supine, Posture::Prone}) {
    const bool shut = posture == Posture::Supine ? c.supine : c.prone;
    const ScanGeometry scan = MakeScan(a, posture, with);
    const ScanGeometry plainScan = MakeScan(MakeAnatomy(without), posture, without);
    const Volume<short> ct = SynthesizeCT(scan, with, none), plain = SynthesizeCT(plainScan, without, none);
    const Volume<unsigned char> lumen = LumenLabel(plainScan, without, none);
    const TubeLocator tube(scan, with.tissue.wallThicknessMm, 1.0);
    long inside = 0, changed = 0, changedElsewhere = 0;
    for (std::size_t v = 0; v < ct.voxels.size(); ++v) {
      if (ct.voxels[v] == plain.voxels[v]) continue;
      const std::size_t i = v % ct.size[0], j = (v / ct.size[0]) % ct.size[1], k = v / (ct.size[0] * ct.size[1]);
      const TubeSample q = tube.Query(ct.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k))));
      ++changed;
      // Changes only within the stretch and its partial-volume step (a few mm of arc length).
      if (!(q.near && q.u > scan.ArcLength(c.s0) - 5.0 && q.u < scan.ArcLength(c.s1) + 5.0)) ++changedElsewhere;
      if (lumen.voxels[v] && q.near && q.u > scan.ArcLength(c.s0) + 3.0 && q.u < scan.ArcLength(c.s1) - 3.0) {
        ++inside;
        EXPECT_GT(ct.voxels[v], -100) << "lumen voxel of the collapsed stretch still air-like";
      }
    }
    EXPECT_EQ(changedElsewhere, 0);
    if (shut) {
      EXPECT_GT(inside, 50);
    } else {
      EXPECT_EQ(changed, 0);  // this scan's lumen is open: the CT is the phantom's without collapses
    }
    // The truth: collapsed=true exactly for the evaluation points in a stretch shut in this scan.
    for (const ControlPoint& p : EvaluationPoints(scan).points) {
      const double s = std::stod(p.description.substr(p.description.find(" s=") + 3));
      const bool expected = shut && s >= c.s0 && s <= c.s1;
      EXPECT_NE(p.description.find(expected ? "collapsed=true" : "collapsed=false"), std::string::npos) << p.description;
    }
  }
}
