// Anatomy from the seed: segment lengths, radii, folds, polyps, taeniae, flexure placement.
#include "PhantomTestUtils.h"

#include <gtest/gtest.h>

using namespace colonmap::phantom;
using namespace colonmap::phantom::testing;

TEST(PhantomAnatomy, SameSeedSameAnatomyOtherSeedDiffers) {
  const ColonAnatomy a = MakeAnatomy(CoarseOptions(7)), b = MakeAnatomy(CoarseOptions(7)), c = MakeAnatomy(CoarseOptions(8));
  EXPECT_EQ(a.length, b.length);
  ASSERT_EQ(a.folds.size(), b.folds.size());
  for (std::size_t i = 0; i < a.folds.size(); ++i) EXPECT_EQ(a.folds[i].s, b.folds[i].s);
  EXPECT_NE(a.length, c.length);
}

TEST(PhantomAnatomy, SegmentLengthsAndRadiiInAnatomicalRanges) {
  for (std::uint32_t seed : {1u, 2u, 3u, 4u}) {
    const ColonAnatomy a = MakeAnatomy(CoarseOptions(seed));
    EXPECT_GT(a.length, 1200.0);
    EXPECT_LT(a.length, 1600.0);
    const double lo[] = {150, 300, 200, 250, 90}, hi[] = {300, 500, 350, 450, 180};
    double prev = 0.0;
    for (int g = 0; g < 5; ++g) {
      const double end = g < 4 ? a.flexureS[g] : a.length;
      EXPECT_GT(end - prev, lo[g]) << SegmentName(g) << " seed " << seed;
      EXPECT_LT(end - prev, hi[g]) << SegmentName(g) << " seed " << seed;
      prev = end;
    }
    EXPECT_NEAR(a.BaseRadius(0.0), 30.0, 3.0);
    EXPECT_NEAR(a.BaseRadius(0.5 * (a.flexureS[kDescendingSigmoid] + a.flexureS[kSigmoidRectum])), 16.0, 2.0);
    const double sr = a.flexureS[kSigmoidRectum];
    EXPECT_NEAR(a.BaseRadius(sr + 0.55 * (a.length - sr)), 25.0, 3.0);
    // Smooth: a gentle taper everywhere (the anal end narrows fastest).
    for (double s = 0.0; s < a.length; s += 1.0) EXPECT_LT(std::fabs(a.radius.Derivative(s)), 0.3) << s;
  }
}

TEST(PhantomAnatomy, HaustralFoldsBetweenTaeniaeAndRectalValves) {
  const ColonAnatomy a = MakeAnatomy(CoarseOptions(3));
  const double sr = a.flexureS[kSigmoidRectum];
  int valves = 0;
  std::vector<double> last(3, -1.0);
  for (const Fold& f : a.folds) {
    EXPECT_GE(f.height, 3.0 - 1e-9);
    EXPECT_LE(f.height, 8.0);
    if (f.sector < 0) {
      ++valves;
      EXPECT_GT(f.s, sr);
      continue;
    }
    EXPECT_LT(f.s, sr);
    if (last[f.sector] >= 0) {
      EXPECT_GE(f.s - last[f.sector], 18.0 - 1e-9);
      EXPECT_LE(f.s - last[f.sector], 35.0 + 1e-9);
    }
    last[f.sector] = f.s;
    // Crescent: deepest mid-sector, zero at both taeniae.
    const double t0 = a.TaeniaTheta(f.sector, f.s), t1 = a.TaeniaTheta((f.sector + 1) % 3, f.s);
    EXPECT_NEAR(a.FoldDepth(f.s, t0 + 1e-9, 0.0), 0.0, 1e-6);
    EXPECT_NEAR(a.FoldDepth(f.s, t1 - 1e-9, 0.0), 0.0, 1e-6);
    EXPECT_NEAR(a.FoldDepth(f.s, t0 + kPi / 3.0, 0.0), f.height, 1e-6);
  }
  EXPECT_EQ(valves, 3);
  // Staggered: the sectors' first folds are at different s.
  EXPECT_NE(a.folds[0].sector, a.folds[1].sector);
  // Valves alternate sides.
  std::vector<double> vt;
  for (const Fold& f : a.folds)
    if (f.sector < 0) vt.push_back(f.valveTheta);
  EXPECT_NEAR(std::fabs(AngleDifference(vt[0], vt[1])), kPi, 1e-9);
}

TEST(PhantomAnatomy, PolypsSizedTypedAndOffTheFolds) {
  bool sessile = false, pedunculated = false;
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const ColonAnatomy a = MakeAnatomy(CoarseOptions(seed));
    ASSERT_GE(a.polyps.size(), 3u);
    ASSERT_LE(a.polyps.size(), 5u);
    for (std::size_t i = 0; i < a.polyps.size(); ++i) {
      const Polyp& p = a.polyps[i];
      EXPECT_EQ(p.label, "P" + std::to_string(i + 1));
      EXPECT_GE(p.diameter, 4.0);
      EXPECT_LE(p.diameter, 15.0);
      EXPECT_EQ(a.FoldDepth(p.s, p.theta, 0.0), 0.0) << p.label << " on a fold";
      EXPECT_NEAR(a.PolypDepth(p.s, p.theta), p.height, 1e-9);
      EXPECT_LT(p.height, 0.5 * a.BaseRadius(p.s));
      (p.pedunculated ? pedunculated : sessile) = true;
    }
  }
  EXPECT_TRUE(sessile);
  EXPECT_TRUE(pedunculated);
}

TEST(PhantomAnatomy, FlexuresOrderedSplenicHighestHepaticSecond) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const PhantomOptions o = CoarseOptions(seed);
    const ColonAnatomy a = MakeAnatomy(o);
    EXPECT_LT(0.0, a.flexureS[0]);
    for (int f = 0; f + 1 < 4; ++f) EXPECT_LT(a.flexureS[f], a.flexureS[f + 1]);
    EXPECT_LT(a.flexureS[3], a.length);
    for (Posture posture : {Posture::Supine, Posture::Prone}) {
      const ScanGeometry scan = MakeScan(a, posture, o);
      double z[4];
      for (int f = 0; f < 4; ++f) z[f] = scan.CenterPoint(a.flexureS[f]).z();
      EXPECT_GT(z[kSplenic], z[kHepatic]);
      EXPECT_GT(z[kHepatic], z[kDescendingSigmoid]);
      EXPECT_GT(z[kHepatic], z[kSigmoidRectum]);
      // Hepatic flexure right (-x), splenic left (+x).
      EXPECT_LT(scan.CenterPoint(a.flexureS[kHepatic]).x(), -40.0);
      EXPECT_GT(scan.CenterPoint(a.flexureS[kSplenic]).x(), 40.0);
      // Cecum right lower, rectum on the posterior midline.
      EXPECT_LT(scan.CenterPoint(0.0).x(), -60.0);
      const Eigen::Vector3d rectum = scan.CenterPoint(0.5 * (a.flexureS[kSigmoidRectum] + a.length));
      EXPECT_LT(std::fabs(rectum.x()), 15.0);
      EXPECT_GT(rectum.y(), 40.0);
    }
  }
}

TEST(PhantomAnatomy, TaeniaeThreeApartWithSlowTwist) {
  const ColonAnatomy a = MakeAnatomy(CoarseOptions(2));
  for (double s : {0.0, 300.0, 900.0}) {
    EXPECT_NEAR(AngleDifference(a.TaeniaTheta(1, s), a.TaeniaTheta(0, s)), 2.0 * kPi / 3.0, 1e-9);
    EXPECT_NEAR(AngleDifference(a.TaeniaTheta(2, s), a.TaeniaTheta(1, s)), 2.0 * kPi / 3.0, 1e-9);
  }
  const double twist = std::fabs(a.TaeniaTheta(0, a.flexureS[kSigmoidRectum]) - a.TaeniaTheta(0, 0.0));
  EXPECT_GT(twist, 0.3 * kPi);
  EXPECT_LT(twist, 1.2 * kPi);
}
