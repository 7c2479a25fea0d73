// The segmentation on the colon phantom at coarse spacing, against the phantom's exact lumen
// (LumenLabel: voxel centres inside the true lumen surface). The CT threshold -480 HU lies
// exactly on the true wall (SynthesizeCT.h), so our air mask and the truth differ only where
// noise (15 HU) moves a voxel across the threshold within a few hundredths of a voxel of the
// wall, plus the voxels the topology growth leaves out: Dice must be close to 1.
#include "SegmentationTestUtils.h"
#include "Core/RecordingProgress.h"
#include "Phantom/Phantom.h"
#include "Segmentation/EulerCharacteristic.h"
#include "Segmentation/LumenSegmentation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <vector>

using namespace colonmap;
using namespace colonmap::segmentation;
using namespace colonmap::segmentation::testing;

namespace {

phantom::PhantomOptions Options(double spacing, bool fluid, std::uint32_t seed) {
  phantom::PhantomOptions o;
  o.seed = seed;
  o.fluid = fluid;
  o.spacing = Eigen::Vector3d(spacing, spacing, spacing);
  return o;
}

struct Case {
  Volume<short> ct;
  Volume<unsigned char> truth;
};
Case Make(const phantom::PhantomOptions& o) {
  NullProgress none;
  const phantom::ColonAnatomy anatomy = phantom::MakeAnatomy(o);
  const phantom::ScanGeometry scan = phantom::MakeScan(anatomy, phantom::Posture::Supine, o);
  return {phantom::SynthesizeCT(scan, o, none), phantom::LumenLabel(scan, o, none)};
}

// The label cropped to its bounding box plus one voxel, so the topology counts stay quick.
Volume<unsigned char> Cropped(const Volume<unsigned char>& m) {
  std::size_t lo[3] = {m.size[0], m.size[1], m.size[2]}, hi[3] = {0, 0, 0};
  for (std::size_t k = 0; k < m.size[2]; ++k)
    for (std::size_t j = 0; j < m.size[1]; ++j)
      for (std::size_t i = 0; i < m.size[0]; ++i)
        if (m.At(i, j, k)) {
          const std::size_t x[3] = {i, j, k};
          for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], x[d]), hi[d] = std::max(hi[d], x[d]);
        }
  Volume<unsigned char> c;
  for (int d = 0; d < 3; ++d) c.size[d] = hi[d] - lo[d] + 3;
  c.Allocate(0);
  for (std::size_t k = lo[2]; k <= hi[2]; ++k)
    for (std::size_t j = lo[1]; j <= hi[1]; ++j)
      for (std::size_t i = lo[0]; i <= hi[0]; ++i) c.At(i - lo[0] + 1, j - lo[1] + 1, k - lo[2] + 1) = m.At(i, j, k);
  return c;
}

struct Agreement {
  double dice, volumeError, outsideTruth;  // outsideTruth: fraction of our voxels not in the truth
};
Agreement Compare(const Volume<unsigned char>& ours, const Volume<unsigned char>& truth) {
  std::size_t a = 0, b = 0, both = 0;
  for (std::size_t v = 0; v < ours.voxels.size(); ++v) {
    a += ours.voxels[v] != 0;
    b += truth.voxels[v] != 0;
    both += ours.voxels[v] && truth.voxels[v];
  }
  return {2.0 * double(both) / double(a + b), (double(a) - double(b)) / double(b), double(a - both) / double(a)};
}

}  // namespace

TEST(PhantomSegmentation, AirFilledColonIsOneBallMatchingTheTruth) {
  for (const double spacing : {2.5, 2.0}) {
    const phantom::PhantomOptions o = Options(spacing, false, 1);
    const Case c = Make(o);
    NullProgress none;
    const LumenSegmentation s = SegmentColonLumen(c.ct, SegmentationOptions{}, none);
    ASSERT_EQ(s.label.size, c.ct.size);
    EXPECT_EQ(s.label.spacing, c.ct.spacing);
    EXPECT_EQ(s.label.origin, c.ct.origin);
    const Volume<unsigned char> crop = Cropped(s.label);
    EXPECT_EQ(Components(crop, 1), 1);
    EXPECT_EQ(Components(crop, 0), 1);  // no cavity
    EXPECT_EQ(EulerCharacteristic(crop), 1);  // one component, no handle, no cavity: a ball
    const Agreement g = Compare(s.label, c.truth);
    const double truthMl = double(CountSet(c.truth)) * o.spacing.prod() / 1000.0;
    std::cout << "spacing " << spacing << " mm: Dice " << g.dice << ", volume error " << 100 * g.volumeError
              << " %, ours " << s.lumenVolumeMl << " ml vs truth " << truthMl << " ml, outside truth "
              << 100 * g.outsideTruth << " %, cavity voxels filled " << s.cavityVoxelsFilled
              << ", handle voxels removed " << s.handleVoxelsRemoved << ", growth " << s.growth.seconds << " s, "
              << s.components.size() << " air components\n";
    EXPECT_GT(g.dice, 0.97);
    EXPECT_LT(std::abs(g.volumeError), 0.03);
    EXPECT_LT(g.outsideTruth, 0.02);
    EXPECT_NEAR(s.lumenVolumeMl, double(CountSet(s.label)) * o.spacing.prod() / 1000.0, 1e-6);
    // The air around the body was seen and dropped; the colon is the kept component.
    ASSERT_LT(s.colon, s.components.size());
    EXPECT_EQ(s.components[s.colon].decision, Decision::Colon);
    EXPECT_GE(s.Dropped(Decision::OutsideBody), 1u);
    EXPECT_EQ(s.components.front().decision, Decision::OutsideBody);  // the largest air is outside
    EXPECT_LE(s.components[s.colon].maxRadiusMm, 40.0);
  }
}

TEST(PhantomSegmentation, UncleansedFluidLeavesTheAirAboveTheLevelAsOneBall) {
  // Tagged fluid is not air: without ColonCleansing only the air part of the lumen is found,
  // and where a pool fills the whole cross-section the air splits; the largest part is kept.
  const phantom::PhantomOptions o = Options(2.5, true, 1);
  const Case c = Make(o);
  NullProgress none;
  const LumenSegmentation s = SegmentColonLumen(c.ct, SegmentationOptions{}, none);
  const Volume<unsigned char> crop = Cropped(s.label);
  EXPECT_EQ(Components(crop, 1), 1);
  EXPECT_EQ(EulerCharacteristic(crop), 1);
  const Agreement g = Compare(s.label, c.truth);
  std::cout << "fluid, not cleansed: Dice " << g.dice << ", volume error " << 100 * g.volumeError << " %, "
            << s.Dropped(Decision::NotLargest) << " further air parts dropped, " << s.Dropped(Decision::TooSmall)
            << " too small\n";
  EXPECT_LT(g.volumeError, 0.0);      // the fluid is missing
  EXPECT_LT(g.outsideTruth, 0.02);    // but what is found is lumen
}

TEST(PhantomSegmentation, NoColonGivesAClearFailure) {
  // The phantom's CT with the colon gas replaced by soft tissue: only the outside air is left.
  const phantom::PhantomOptions o = Options(2.5, false, 2);
  Case c = Make(o);
  for (std::size_t v = 0; v < c.ct.voxels.size(); ++v)
    if (c.truth.voxels[v]) c.ct.voxels[v] = 40;
  NullProgress none;
  try {
    SegmentColonLumen(c.ct, SegmentationOptions{}, none);
    FAIL() << "no failure";
  } catch (const NoColonFound& e) {
    EXPECT_NE(std::string(e.what()).find("no distended colon found"), std::string::npos) << e.what();
  }
  // A high minimum volume rejects the colon itself, and the message gives its volume.
  const Case d = Make(o);
  SegmentationOptions strict;
  strict.minColonVolumeMl = 1e5;
  try {
    SegmentColonLumen(d.ct, strict, none);
    FAIL() << "no failure";
  } catch (const NoColonFound& e) {
    EXPECT_NE(std::string(e.what()).find("the largest air component inside the body is"), std::string::npos) << e.what();
  }
  SegmentationOptions thin;
  thin.maxColonRadiusMm = 5.0;
  EXPECT_THROW(SegmentColonLumen(d.ct, thin, none), NoColonFound);
  SegmentationOptions bad;
  bad.airThresholdHU = 100.0;
  EXPECT_THROW(SegmentColonLumen(d.ct, bad, none), Error);
}

TEST(PhantomSegmentation, LungLikeAndSmallComponentsAreDropped) {
  // The phantom plus a thick air ball (lung-like, 45 mm radius) and a small pocket (6 mm) in
  // the body, each placed where it keeps 8 mm from the true lumen (so apart from the colon gas).
  const phantom::PhantomOptions o = Options(2.5, false, 1);
  Case c = Make(o);
  std::vector<Eigen::Vector3d> lumen;
  for (std::size_t k = 0; k < c.ct.size[2]; ++k)
    for (std::size_t j = 0; j < c.ct.size[1]; ++j)
      for (std::size_t i = 0; i < c.ct.size[0]; ++i)
        if (c.truth.At(i, j, k)) lumen.push_back(c.ct.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k))));
  const auto place = [&](double radius) {  // highest free place inside 70 % of the body ellipse
    for (double z = 200.0 - radius; z > -230.0 + radius; z -= 10.0)
      for (double y = -80.0; y <= 80.0; y += 10.0)
        for (double x = -110.0; x <= 110.0; x += 10.0) {
          const Eigen::Vector3d p(x, y, z);
          if (std::pow((std::abs(x) + radius) / 172.0, 2) + std::pow((std::abs(y) + radius) / 135.0, 2) > 0.49) continue;
          bool free = true;
          for (const Eigen::Vector3d& q : lumen)
            if ((q - p).squaredNorm() < (radius + 8.0) * (radius + 8.0)) {
              free = false;
              break;
            }
          if (free) return p;
        }
    ADD_FAILURE() << "no free place for a ball of radius " << radius;
    return Eigen::Vector3d(0, 0, 0);
  };
  const Eigen::Vector3d lung = place(45.0), pocket = place(6.0);
  std::size_t lungVoxels = 0;
  for (std::size_t k = 0; k < c.ct.size[2]; ++k)
    for (std::size_t j = 0; j < c.ct.size[1]; ++j)
      for (std::size_t i = 0; i < c.ct.size[0]; ++i) {
        const Eigen::Vector3d p = c.ct.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
        if ((p - lung).norm() < 45.0 || (p - pocket).norm() < 6.0) {
          c.ct.At(i, j, k) = -900;
          lungVoxels += (p - lung).norm() < 45.0;
        }
      }
  NullProgress none;
  const LumenSegmentation s = SegmentColonLumen(c.ct, SegmentationOptions{}, none);
  EXPECT_EQ(s.Dropped(Decision::TooThick), 1u);
  EXPECT_GE(s.Dropped(Decision::TooSmall), 1u);
  for (const AirComponent& a : s.components) {
    if (a.decision == Decision::TooThick) {
      EXPECT_NEAR(double(a.voxels), double(lungVoxels), lungVoxels / 50.0);
    }
  }
  EXPECT_GT(Compare(s.label, c.truth).dice, 0.97);
}

TEST(PhantomSegmentation, Cancels) {
  const Case c = Make(Options(2.5, false, 1));
  RecordingProgress progress(5);
  EXPECT_THROW(SegmentColonLumen(c.ct, SegmentationOptions{}, progress), Cancelled);
}
