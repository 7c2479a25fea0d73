// Electronic cleansing against the phantom's exact answer: the same phantom CT without fluid
// (the CT noise is a function of the voxel, so an ideal cleansing reproduces it voxel by voxel
// wherever the wall is not hidden in a three-material mixture).
#include "Cleansing/ElectronicCleansing.h"
#include "Core/RecordingProgress.h"
#include "Phantom/Phantom.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

using namespace colonmap;
using namespace colonmap::cleansing;
using namespace colonmap::phantom;

namespace {

struct Pair {
  Volume<short> withFluid, withoutFluid;
};

Pair MakePair(Posture posture, std::uint32_t seed, double spacing) {
  PhantomOptions o;
  o.seed = seed;
  o.spacing = Eigen::Vector3d::Constant(spacing);
  NullProgress none;
  const ColonAnatomy anatomy = MakeAnatomy(o);
  const ScanGeometry scan = MakeScan(anatomy, posture, o);
  Pair p;
  p.withFluid = SynthesizeCT(scan, o, none);
  o.fluid = false;
  p.withoutFluid = SynthesizeCT(scan, o, none);
  return p;
}

struct Agreement {
  std::size_t affected = 0;      // voxels the fluid changed by more than 100 HU
  std::size_t close = 0;         // of those, cleansed within 100 HU of the fluid-free CT
  std::size_t sideFlips = 0;     // voxels on the other side of the half-way value (-480)
  std::size_t boundary = 0;      // fluid-free voxels within 300 HU of -480 in the affected zone
  std::size_t residue = 0;       // flips that leave wall-like values in the lumen (a ridge)
  std::size_t boundaryOff = 0;   // boundary voxels off by more than 520 HU (about one voxel of shift)
  std::size_t spoiled = 0;       // voxels the fluid did not change that cleansing moved by more than 100 HU
};

Agreement Compare(const Volume<short>& cleansed, const Pair& p) {
  Agreement a;
  for (std::size_t o = 0; o < cleansed.voxels.size(); ++o) {
    const int truth = p.withoutFluid.voxels[o];
    if (std::abs(p.withFluid.voxels[o] - truth) <= 100) {
      if (std::abs(cleansed.voxels[o] - truth) > 100) ++a.spoiled;
      continue;
    }
    ++a.affected;
    if (std::abs(cleansed.voxels[o] - truth) <= 100) ++a.close;
    if ((cleansed.voxels[o] < -480) != (truth < -480)) {
      ++a.sideFlips;
      if (truth < -480) ++a.residue;
    }
    if (std::abs(truth + 480) < 300) {
      ++a.boundary;
      if (std::abs(cleansed.voxels[o] - truth) > 520) ++a.boundaryOff;
    }
  }
  return a;
}

}  // namespace

TEST(Cleansing, UntaggedScanPassesThroughUnchanged) {
  PhantomOptions o;
  o.spacing = Eigen::Vector3d::Constant(2.5);
  o.fluid = false;
  NullProgress none;
  const ColonAnatomy anatomy = MakeAnatomy(o);
  const Volume<short> ct = SynthesizeCT(MakeScan(anatomy, Posture::Supine, o), o, none);
  const CleansingResult r = Cleanse(ct, CleansingParameters(), none);
  EXPECT_EQ(r.taggedVoxels, 0u);
  EXPECT_EQ(r.regions, 0u);
  EXPECT_TRUE(r.cleansed.voxels == ct.voxels);
}

TEST(Cleansing, PhantomPoolsBecomeAirWithTheWallKept) {
  for (Posture posture : {Posture::Supine, Posture::Prone}) {
    const Pair p = MakePair(posture, 2, 1.5);
    NullProgress none;
    const CleansingResult r = Cleanse(p.withFluid, CleansingParameters(), none);
    const Agreement a = Compare(r.cleansed, p);
    const Agreement before = Compare(p.withFluid, p);
    const char* name = posture == Posture::Supine ? "supine" : "prone";
    std::cout << name << ": affected " << a.affected << " voxels, within 100 HU " << a.close
              << ", side flips at -480 HU " << a.sideFlips << " (residue " << a.residue << ")" << " (before cleansing " << before.sideFlips
              << "), spoiled " << a.spoiled << ", boundary voxels " << a.boundary << " of which off by > 520 HU " << a.boundaryOff << ", fluid " << r.fluidHU << " HU, down "
              << r.down.transpose() << " agreement " << r.gravityAgreement << "\n";
    ASSERT_GT(a.affected, 1000u) << "the phantom should have fluid pools";
    // Gravity found from the levels: supine posterior (+y), prone anterior (-y).
    EXPECT_GT(r.down.y() * (posture == Posture::Supine ? 1.0 : -1.0), 0.95);
    // Nearly all voxels the fluid changed are back to their fluid-free value (measured 99.5% /
    // 99.7%; 97.5% / 96.4% before the films of shallow pools were cleansed); the rest are
    // three-material voxels (air, fluid, wall) where the lumen's mixture is as bright as wall.
    EXPECT_GT(double(a.close) / double(a.affected), 0.99);
    // The lumen boundary (half-way value) is where it is without fluid: no boundary voxel is off
    // by a voxel's worth of HU (measured 0 / 0; 86 / 13 before), and the side of -480 HU is
    // restored for nearly all voxels (274 / 89 left of 36529 / 8231; 580 / 227 before).
    EXPECT_LT(double(a.boundaryOff), 0.01 * double(a.boundary));
    EXPECT_LT(a.sideFlips * 50, before.sideFlips);
    // Voxels the fluid did not touch stay as they are: the three-material model is applied only
    // where a film can be (measured 86 / 61 moved by > 100 HU, 0.2% / 0.5% of the affected
    // count; 6 / 5 before films were cleansed, 234 / 202 without the tissue-below test).
    EXPECT_LT(double(a.spoiled), 0.01 * double(a.affected));
    EXPECT_GT(r.taggedVoxels, a.affected / 2);
  }
}

TEST(Cleansing, BrightTissueAwayFromAirIsKept) {
  Pair p = MakePair(Posture::Supine, 3, 2.5);
  // A bone-like block deep in the body fat, touching no air.
  Volume<short> ct = p.withFluid;
  const Eigen::Vector3d centre = ct.PhysicalToIndex(Eigen::Vector3d(0.0, 60.0, -15.0));
  for (int dk = -3; dk <= 3; ++dk)
    for (int dj = -3; dj <= 3; ++dj)
      for (int di = -3; di <= 3; ++di)
        ct.At(std::size_t(centre.x() + di), std::size_t(centre.y() + dj), std::size_t(centre.z() + dk)) = 1200;
  NullProgress none;
  const CleansingResult r = Cleanse(ct, CleansingParameters(), none);
  EXPECT_GE(r.regionsDropped, 1u);
  EXPECT_EQ(r.cleansed.At(std::size_t(centre.x()), std::size_t(centre.y()), std::size_t(centre.z())), 1200);
}

TEST(Cleansing, CancelStopsTheWork) {
  const Pair p = MakePair(Posture::Supine, 1, 2.5);
  RecordingProgress cancel(5);
  EXPECT_THROW(Cleanse(p.withFluid, CleansingParameters(), cancel), Cancelled);
}
