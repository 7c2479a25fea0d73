// No ridge where the air-fluid level was (issue 4): the phantom with fluid pools is cleansed,
// and the wall is reconstructed from the cleansed CT (with the exact lumen label, so that only
// the cleansing differs) and from the same scan made without fluid. Along the former levels
// (vertices within 1.5 mm of a pool's level height) the mean curvature is compared with the
// fluid-free wall at the same places, and the wall with where it truly is.
// APPROXIMATE (issue 4 open): a ridge remains. Measured (1.5 mm, seed 2, supine/prone): curvature
// SD 0.161/0.139 mm^-1 against 0.083/0.071 fluid-free, distance to the true wall mean 0.27/0.24 mm,
// max 1.87/1.44 mm (fluid-free 0.03, 0.22). Three-material handling of the level band brought
// them down from SD 0.218/0.207 and mean 0.33/0.29 mm; what remains sits where the level grazes
// the wall (the rim of shallow pools), where the voxel values cannot tell a thin fluid film from
// wall. The bounds below hold today's figures with a small margin, so a regression fails.
#include "Surface/SurfaceReconstruction.h"
#include "SurfaceDistance.h"

#include "Cleansing/ElectronicCleansing.h"
#include "Phantom/Phantom.h"
#include "Phantom/TubeLocator.h"

#include <gtest/gtest.h>

#include <cmath>
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

TEST(FormerFluidLevels, NoRidgeWhereTheLevelWas) {
  for (Posture posture : {Posture::Supine, Posture::Prone}) {
    PhantomOptions o;
    o.seed = 2;
    o.spacing = Eigen::Vector3d::Constant(1.5);
    NullProgress none;
    const ScanGeometry scan = MakeScan(MakeAnatomy(o), posture, o);
    const Volume<short> withFluid = SynthesizeCT(scan, o, none);
    const cleansing::CleansingResult cleansed = cleansing::Cleanse(withFluid, cleansing::CleansingParameters(), none);
    PhantomOptions dry = o;
    dry.fluid = false;
    const Volume<short> withoutFluid = SynthesizeCT(scan, dry, none);
    const Volume<unsigned char> lumen = LumenLabel(scan, o, none);
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
    ASSERT_GT(level.n, 100) << "the phantom should have fluid levels meeting the wall";
    EXPECT_LT(level.sdH, 2.2 * levelDry.sdH) << "a ridge along the former level";
    EXPECT_LT(level.meanDistance, 0.32);
    EXPECT_LT(level.maxDistance, 2.2);
  }
}

}  // namespace
}  // namespace colonmap::surface
