// No ridge where the air-fluid level was (issue 4): the phantom with fluid pools is cleansed,
// and the wall is reconstructed from the cleansed CT and from the same scan made without fluid,
// both with one lumen label (our segmentation of the fluid-free scan), so that only the
// cleansing differs. Along the former levels
// (vertices within 1.5 mm of a pool's level height) the mean curvature is compared with the
// fluid-free wall at the same places, and the wall with where it truly is.
// Measured (1.5 mm, seed 2, supine/prone): curvature SD 0.082/0.081 mm^-1 against 0.083/0.071
// fluid-free and 0.082/0.078 on the wall around; distance to the true wall mean 0.057/0.045 mm,
// max 0.52/0.71 mm (fluid-free 0.03, 0.22). Seeds 1-6 (DISABLED_SurveySeeds1To6; the bounds
// below are seed 2's; in 1 of the 12 scans, seed 5 prone, both surfaces come from the label
// alone, identical figures, left out): SD 0.072-0.128, 0.99-1.26 times the fluid-free scan's at
// the same places; mean distance 0.043-0.088 mm, max <= 1.14 mm. History (ElectronicCleansing.cxx): the three-material level band alone gave seed 2
// SD 0.161/0.139, mean 0.27/0.24 mm, max 1.87/1.44 (seeds 1-6: SD 0.106-0.257, mean 0.11-0.43,
// max <= 1.94): the films of shallow pools, where no fluid core lies below, read as wall and the
// surface sat up to half a voxel inside the lumen on floors nearly parallel to the level.
// Cleansing those films too: 0.092/0.085, 0.079/0.050 mm; interpolating the quantile of the lumen
// fraction, not the fraction, across the ill-conditioned voxel layer (lumen mixture as bright as
// wall): today's figures. The bounds hold them with a margin.
#include "Surface/SurfaceReconstruction.h"
#include "SurfaceDistance.h"

#include "Cleansing/ElectronicCleansing.h"
#include "Phantom/Phantom.h"
#include "Phantom/TubeLocator.h"
#include "Segmentation/LumenSegmentation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>

namespace colonmap::surface {
namespace {

using namespace colonmap::phantom;

constexpr double kLevelBandMm = 1.5;        // "along the level": this close to its height
constexpr double kAroundMm[2] = {3.0, 10.0};  // "the wall around": this far above or below it

struct BandStats {
  long n = 0;
  double sdH = 0.0, meanDistance = 0.0, maxDistance = 0.0;
};

// Curvature spread and distance to the true wall of the vertices whose height lies within
// [lo, hi) mm of their pool's level.
BandStats Band(const SurfaceResult& s, const ScanGeometry& scan, const PhantomOptions& o, const TriangleMesh& truth,
               double lo, double hi) {
  const TubeLocator tube(scan, o.tissue.wallThicknessMm, 3.0);
  const Eigen::VectorXd& H = s.mesh.pointData.at("MeanCurvature").values;
  const testing::ClosestPoints toTruth = testing::ClosestOnSurface(truth.V, truth.F, s.mesh.V);
  BandStats b;
  double sum = 0.0, sum2 = 0.0, dist = 0.0;
  for (long v = 0; v < s.mesh.V.rows(); ++v) {
    const Eigen::Vector3d p = s.mesh.V.row(v).transpose();
    const TubeSample q = tube.Query(p);
    if (!q.near || q.end != 0) continue;
    const FluidPool* pool = scan.PoolAt(q.u);
    if (!pool) continue;
    const double d = std::abs(pool->level - scan.Height(p));
    if (d < lo || d >= hi) continue;
    ++b.n;
    sum += H(v);
    sum2 += H(v) * H(v);
    dist += toTruth.distance(v);
    b.maxDistance = std::max(b.maxDistance, toTruth.distance(v));
  }
  if (b.n > 1) {
    b.sdH = std::sqrt(std::max(0.0, sum2 / b.n - (sum / b.n) * (sum / b.n)));
    b.meanDistance = dist / b.n;
  }
  return b;
}

// One seed, both postures; strict: assert the bounds (seed 2's figures with a margin), else only
// print (the survey over other seeds).
void FormerLevels(std::uint32_t seed, bool strict) {
  for (Posture posture : {Posture::Supine, Posture::Prone}) {
    PhantomOptions o;
    o.seed = seed;
    o.spacing = Eigen::Vector3d::Constant(1.5);
    NullProgress none;
    const ScanGeometry scan = MakeScan(MakeAnatomy(o), posture, o);
    const Volume<short> withFluid = SynthesizeCT(scan, o, none);
    const cleansing::CleansingResult cleansed = cleansing::Cleanse(withFluid, cleansing::CleansingParameters(), none);
    PhantomOptions dry = o;
    dry.fluid = false;
    const Volume<short> withoutFluid = SynthesizeCT(scan, dry, none);
    // The label both surfaces share: our segmentation of the fluid-free scan (genus 0, as the
    // pipeline's labels are; the phantom's exact lumen touches itself at 1.5 mm in some scans,
    // and a label with a handle sends both reconstructions to the label-only fallback).
    const Volume<unsigned char> lumen = segmentation::SegmentColonLumen(withoutFluid, {}, none).label;
    Volume<float> label = lumen.Like<float>(0.0f);
    for (std::size_t i = 0; i < lumen.voxels.size(); ++i) label.voxels[i] = lumen.voxels[i];
    SurfaceOptions so;
    so.targetFaces = 120000;
    const SurfaceResult fromCleansed = ReconstructSurface(label, &cleansed.cleansed, so, none);
    const SurfaceResult fromDry = ReconstructSurface(label, &withoutFluid, so, none);
    const TriangleMesh truth = TrueWall(scan, o);

    const BandStats level = Band(fromCleansed, scan, o, truth, 0.0, kLevelBandMm);
    const BandStats levelDry = Band(fromDry, scan, o, truth, 0.0, kLevelBandMm);
    const BandStats around = Band(fromCleansed, scan, o, truth, kAroundMm[0], kAroundMm[1]);
    std::printf("%s: former levels %ld vertices, curvature SD %.3f mm^-1 (fluid-free scan %.3f, wall around %.3f); "
                "distance to the true wall mean %.3f max %.3f mm (fluid-free %.3f, %.3f)\n",
                posture == Posture::Supine ? "supine" : "prone", level.n, level.sdH, levelDry.sdH, around.sdH,
                level.meanDistance, level.maxDistance, levelDry.meanDistance, levelDry.maxDistance);
    if (!strict) continue;
    ASSERT_GT(level.n, 100) << "the phantom should have fluid levels meeting the wall";
    // Both from the CT (a label-only fallback of both would compare a surface with itself).
    ASSERT_TRUE(fromCleansed.usedCT && fromDry.usedCT);
    EXPECT_LT(level.sdH, 1.25 * levelDry.sdH) << "a ridge along the former level";
    EXPECT_LT(level.sdH, 1.2 * around.sdH) << "a ridge along the former level";
    EXPECT_LT(level.meanDistance, 0.1);
    EXPECT_LT(level.maxDistance, 1.0);
  }
}

TEST(FormerFluidLevels, NoRidgeWhereTheLevelWas) { FormerLevels(2, true); }

// The survey of the header (seeds 1-6; prints only): --gtest_also_run_disabled_tests.
TEST(FormerFluidLevels, DISABLED_SurveySeeds1To6) {
  for (std::uint32_t seed = 1; seed <= 6; ++seed) {
    std::printf("seed %u\n", seed);
    FormerLevels(seed, false);
  }
}

}  // namespace
}  // namespace colonmap::surface
