// Synthetic CT at coarse spacing: determinism, the true wall on the CT boundary, tissues,
// tagged fluid with flat levels, progress and cancellation.
#include "PhantomTestUtils.h"

#include <gtest/gtest.h>

using namespace colonmap;
using namespace colonmap::phantom;
using namespace colonmap::phantom::testing;

namespace {
struct CountingProgress : ProgressSink {
  int calls = 0, cancelAfter = -1;
  double last = -1.0;
  bool monotone = true;
  void Report(double f) override {
    if (f < last) monotone = false;
    last = f;
    if (++calls == cancelAfter) throw Cancelled();
  }
};

// Wall vertices where the surface is smooth on the scale of the voxel (no fold or polyp
// within two voxels) and dry (above every pool level by two partial-volume widths).
bool SmoothDryWall(const ScanGeometry& scan, double s, double theta, double h, const Eigen::Vector3d& x, double W) {
  const ColonAnatomy& a = scan.anatomy;
  const double dt = h / a.BaseRadius(s);
  for (int i = -2; i <= 2; ++i)
    for (int j = -2; j <= 2; ++j)
      if (a.FoldDepth(s + i * h, theta + j * dt, 1.0) > 0.0 || a.PolypDepth(s + i * h, theta + j * dt) > 0.0) return false;
  for (const FluidPool& p : scan.pools)
    if (scan.Height(x) < p.level + 2.0 * W + 3.0) return false;
  return true;
}
}  // namespace

TEST(PhantomCT, DeterministicAndSeeded) {
  const PhantomOptions o = CoarseOptions(1, 0.5);
  const ColonAnatomy a = MakeAnatomy(o);
  NullProgress np;
  const Volume<short> v1 = SynthesizeCT(MakeScan(a, Posture::Prone, o), o, np);
  const Volume<short> v2 = SynthesizeCT(MakeScan(MakeAnatomy(o), Posture::Prone, o), o, np);
  EXPECT_TRUE(v1.voxels == v2.voxels);
  EXPECT_EQ(v1.size, v2.size);
  EXPECT_EQ(v1.origin, v2.origin);
  PhantomOptions other = o;
  other.seed = 2;
  const Volume<short> v3 = SynthesizeCT(MakeScan(MakeAnatomy(other), Posture::Prone, other), other, np);
  EXPECT_FALSE(v1.voxels == v3.voxels);
  // Clinical grid geometry, without synthesising it.
  PhantomOptions clinical;
  const Volume<short> g = CTGrid(clinical);
  EXPECT_EQ(g.size[0], 512u);
  EXPECT_EQ(g.size[1], 512u);
  EXPECT_EQ(g.size[2], 450u);
  EXPECT_TRUE(g.voxels.empty());
}

TEST(PhantomCT, TrueWallIsTheHalfWayBoundary) {
  PhantomOptions o = CoarseOptions(2, 0.5);
  o.meshPointsAround = 64;
  o.meshStepMm = 3.0;
  const ColonAnatomy a = MakeAnatomy(o);
  const double W = PartialVolumeHalfWidth(o);
  const double half = 0.5 * (o.tissue.airHU + o.tissue.wallHU), range = o.tissue.wallHU - o.tissue.airHU;
  NullProgress np;
  for (Posture posture : {Posture::Supine, Posture::Prone}) {
    const ScanGeometry scan = MakeScan(a, posture, o);
    const Volume<short> ct = SynthesizeCT(scan, o, np);
    const TriangleMesh w = TrueWall(scan, o);
    const auto& S = w.pointData.at("MaterialS").values;
    const auto& T = w.pointData.at("MaterialTheta").values;
    int n = 0, within = 0;
    std::vector<double> err;
    for (Eigen::Index v = 0; v < w.V.rows(); ++v) {
      const Eigen::Vector3d x = w.V.row(v);
      if (S(v, 0) < 5.0 || S(v, 0) > a.length - 5.0 || !SmoothDryWall(scan, S(v, 0), T(v, 0), 2.5, x, W)) continue;
      const double e = std::fabs(Trilinear(ct, x) - half);
      ++n;
      within += e < 0.25 * range;
      err.push_back(e);
    }
    ASSERT_GT(n, 2000);
    std::sort(err.begin(), err.end());
    EXPECT_GT(within, 0.99 * n) << "posture " << int(posture);
    EXPECT_LT(err[err.size() / 2], 0.08 * range);
    // A step of one voxel into the lumen is air, one voxel out is (mostly) wall.
    for (Eigen::Index v = 0; v < w.V.rows(); v += 97) {
      const Eigen::Vector3d x = w.V.row(v);
      if (S(v, 0) < 5.0 || S(v, 0) > a.length - 5.0 || !SmoothDryWall(scan, S(v, 0), T(v, 0), 2.5, x, W)) continue;
      const Eigen::Vector3d d = scan.RadialDirection(S(v, 0), T(v, 0));
      EXPECT_LT(Trilinear(ct, x - 2.0 * W * d), -850.0);
      EXPECT_GT(Trilinear(ct, x + 1.5 * d), half + 0.25 * range);
    }
  }
}

TEST(PhantomCT, FinerGridFollowsFoldsToo) {
  // 0.8 mm voxels in a box around part of the transverse colon: the surface is on the
  // boundary also across folds (the coarse grid cannot resolve 3-5 mm wide folds).
  PhantomOptions o = CoarseOptions(1, 0.5);
  o.spacing = Eigen::Vector3d::Constant(0.8);
  o.meshPointsAround = 96;
  const ColonAnatomy a = MakeAnatomy(o);
  const ScanGeometry scan = MakeScan(a, Posture::Supine, o);
  const double s0 = 0.5 * (a.flexureS[kHepatic] + a.flexureS[kSplenic]);
  const Eigen::Vector3d c = scan.CenterPoint(s0);
  Volume<short> box;
  box.size = {{75, 75, 75}};
  box.spacing = o.spacing;
  box.origin = c - Eigen::Vector3d::Constant(37 * 0.8);
  NullProgress np;
  SynthesizeCTOnGrid(scan, o, box, np);
  const TriangleMesh w = TrueWall(scan, o);
  const double half = -480.0, range = 1040.0;
  int n = 0, within = 0;
  const Eigen::Vector3d lo = box.origin + Eigen::Vector3d::Constant(3.0), hi = box.IndexToPhysical(Eigen::Vector3d(74, 74, 74)) - Eigen::Vector3d::Constant(3.0);
  for (Eigen::Index v = 0; v < w.V.rows(); ++v) {
    const Eigen::Vector3d x = w.V.row(v);
    if ((x.array() < lo.array()).any() || (x.array() > hi.array()).any()) continue;
    bool wet = false;
    for (const FluidPool& p : scan.pools) wet = wet || scan.Height(x) < p.level + 5.0;
    if (wet) continue;
    ++n;
    within += std::fabs(Trilinear(box, x) - half) < 0.25 * range;
  }
  ASSERT_GT(n, 500);
  EXPECT_GT(within, 0.95 * n);
}

TEST(PhantomCT, TissuesLumenAndBody) {
  PhantomOptions o = CoarseOptions(3, 0.5);
  o.fluid = false;
  const ColonAnatomy a = MakeAnatomy(o);
  const ScanGeometry scan = MakeScan(a, Posture::Supine, o);
  NullProgress np;
  const Volume<short> ct = SynthesizeCT(scan, o, np);
  // No fluid: nothing bright.
  EXPECT_EQ(std::count_if(ct.voxels.begin(), ct.voxels.end(), [](short v) { return v > 300; }), 0);
  // Deep lumen (on the centreline) is air; fat far from the colon is fat; outside is air.
  for (double s = 10.0; s < a.length - 10.0; s += 25.0) EXPECT_LT(Trilinear(ct, scan.CenterPoint(s)), -900.0) << s;
  const TubeLocator tube(scan, 3.0, 10.0);
  int fat = 0;
  for (double x = -120; x <= 120; x += 20)
    for (double z = -200; z <= 180; z += 40) {
      const Eigen::Vector3d p(x, -100.0 * 0 + 0.0, z);
      if (tube.Query(p).near) continue;
      const double hu = Trilinear(ct, p);
      EXPECT_NEAR(hu, o.tissue.fatHU, 60.0) << x << " " << z;
      ++fat;
    }
  EXPECT_GT(fat, 50);
  EXPECT_NEAR(Trilinear(ct, Eigen::Vector3d(0.0, 160.0, 0.0)), o.tissue.airHU, 60.0);
  EXPECT_NEAR(Trilinear(ct, Eigen::Vector3d(0.0, -o.tissue.bodySemiAxisYMm + 6.0, 0.0)), o.tissue.softTissueHU, 60.0);
  // Both ends are closed: beyond the cecum and the anus along the centreline, past the cap.
  Eigen::Vector3d T, N, B;
  scan.centerline.Frame(0.0, T, N, B);
  EXPECT_LT(Trilinear(ct, scan.CenterPoint(0.0) - 0.5 * a.BaseRadius(0.0) * T), -900.0);
  EXPECT_GT(Trilinear(ct, scan.CenterPoint(0.0) - (a.BaseRadius(0.0) * 1.1 + 4.0) * T), -300.0);
  // The lumen label agrees with the CT: label voxels are dark on average.
  const Volume<unsigned char> label = LumenLabel(scan, o, np);
  double sum = 0;
  long count = 0;
  for (std::size_t i = 0; i < label.voxels.size(); ++i)
    if (label.voxels[i]) sum += ct.voxels[i], ++count;
  EXPECT_GT(count, 10000);
  EXPECT_LT(sum / count, -800.0);
}

TEST(PhantomCT, TaggedFluidPoolsAtTheDependentSideWithFlatLevels) {
  for (Posture posture : {Posture::Supine, Posture::Prone}) {
    PhantomOptions o = CoarseOptions(1, 0.5);
    const ColonAnatomy a = MakeAnatomy(o);
    const ScanGeometry scan = MakeScan(a, posture, o);
    ASSERT_GE(scan.pools.size(), 2u);
    EXPECT_GE(scan.fluidHU, 600.0);
    EXPECT_LE(scan.fluidHU, 900.0);
    NullProgress np;
    const Volume<short> ct = SynthesizeCT(scan, o, np);
    const TubeLocator tube(scan, 3.0, 3.0);
    // Every bright voxel is fluid of a pool, below that pool's level.
    long bright = 0;
    for (std::size_t k = 0; k < ct.size[2]; ++k)
      for (std::size_t j = 0; j < ct.size[1]; ++j)
        for (std::size_t i = 0; i < ct.size[0]; ++i) {
          if (ct.At(i, j, k) <= 300) continue;
          ++bright;
          const Eigen::Vector3d p = ct.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
          const TubeSample q = tube.Query(p);
          ASSERT_TRUE(q.near);
          const FluidPool* pool = scan.PoolAt(q.u);
          ASSERT_NE(pool, nullptr);
          EXPECT_LT(scan.Height(p), pool->level) << "above the level";
        }
    EXPECT_GT(bright, 200);
    // The dependent side of each pool is bright: just inside the lowest wall point.
    for (const FluidPool& pool : scan.pools) {
      const double s = scan.MaterialS(pool.deepestU);
      double best = 1e300, bt = 0;
      for (int k = 0; k < 180; ++k) {
        const double h = scan.Height(scan.WallPoint(s, 2 * kPi * k / 180));
        if (h < best) best = h, bt = 2 * kPi * k / 180;
      }
      ASSERT_LT(best, pool.level - 5.0);
      const Eigen::Vector3d inside = scan.WallPoint(s, bt) - 3.5 * scan.RadialDirection(s, bt);
      EXPECT_GT(Trilinear(ct, inside), 300.0);
      // Gravity: supine pools lie posterior (+y) of their centreline, prone anterior.
      const double dy = scan.WallPoint(s, bt).y() - scan.CenterPoint(s).y();
      EXPECT_GT(posture == Posture::Supine ? dy : -dy, 0.0);
    }
  }
}

TEST(PhantomCT, ReportsProgressAndCanBeCancelled) {
  const PhantomOptions o = CoarseOptions(1, 0.5);
  const ScanGeometry scan = MakeScan(MakeAnatomy(o), Posture::Supine, o);
  CountingProgress p;
  SynthesizeCT(scan, o, p);
  EXPECT_GE(p.calls, 5);
  EXPECT_TRUE(p.monotone);
  EXPECT_EQ(p.last, 1.0);
  CountingProgress c;
  c.cancelAfter = 3;
  EXPECT_THROW(SynthesizeCT(scan, o, c), Cancelled);
}
