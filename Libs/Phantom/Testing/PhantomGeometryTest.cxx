// Supine and prone embeddings: clearance, bend radius, body fit, supine->prone behaviour.
#include "PhantomTestUtils.h"

#include <gtest/gtest.h>

using namespace colonmap::phantom;
using namespace colonmap::phantom::testing;

namespace {
// Checks (1) curvature * outer radius < 1 (unique nearest centreline point in the wall band) and
// (2) non-adjacent centreline samples are farther apart than the sum of their outer radii.
// Non-adjacent: more than pi * max(radius) apart along the curve (with bend radius > radius,
// closer samples are neighbours on one smooth bend).
void ExpectNoSelfIntersection(const ScanGeometry& scan, const std::string& what) {
  const double wall = 3.0, L = scan.centerline.Length();
  std::vector<Eigen::Vector3d> c;
  std::vector<double> u, ro;
  for (double x = 0.0; x <= L; x += 2.0) {
    c.push_back(scan.centerline.Point(x));
    u.push_back(x);
    ro.push_back(MaxOuterRadius(scan, scan.MaterialS(x), wall));
  }
  double worstBend = 0.0, worstGap = 1e300;
  for (std::size_t i = 0; i < c.size(); ++i) {
    worstBend = std::max(worstBend, scan.centerline.Curvature(u[i]) * ro[i]);
    for (std::size_t j = i + 1; j < c.size(); ++j) {
      if (u[j] - u[i] <= kPi * std::max(ro[i], ro[j])) continue;
      worstGap = std::min(worstGap, (c[i] - c[j]).norm() - ro[i] - ro[j]);
    }
  }
  EXPECT_LT(worstBend, 1.0) << what;
  EXPECT_GT(worstGap, 1.0) << what;
}
}  // namespace

TEST(PhantomGeometry, NoSelfIntersectionAndBendRadiusAboveTubeRadius) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    for (double def : {0.0, 0.5, 1.0}) {
      const PhantomOptions o = CoarseOptions(seed, def);
      const ColonAnatomy a = MakeAnatomy(o);
      ExpectNoSelfIntersection(MakeScan(a, Posture::Prone, o), "prone seed " + std::to_string(seed) + " def " + std::to_string(def));
      if (def == 0.0) ExpectNoSelfIntersection(MakeScan(a, Posture::Supine, o), "supine seed " + std::to_string(seed));
    }
  }
}

TEST(PhantomGeometry, TubeInsideTheBodyFat) {
  for (double def : {0.0, 1.0}) {
    const PhantomOptions o = CoarseOptions(2, def);
    const ColonAnatomy a = MakeAnatomy(o);
    for (Posture posture : {Posture::Supine, Posture::Prone}) {
      const ScanGeometry scan = MakeScan(a, posture, o);
      const TissueModel& t = o.tissue;
      const double ax = t.bodySemiAxisXMm - t.bodyRimMm, ay = t.bodySemiAxisYMm - t.bodyRimMm;
      const Eigen::Vector3d lo = o.tissue.fieldOfViewCentre - 0.5 * o.tissue.fieldOfViewMm;
      const Eigen::Vector3d hi = o.tissue.fieldOfViewCentre + 0.5 * o.tissue.fieldOfViewMm;
      for (double s = 0.0; s <= a.length; s += 2.0)
        for (int k = 0; k < 32; ++k) {
          const double th = 2 * kPi * k / 32;
          const Eigen::Vector3d p = scan.CenterPoint(s) + (scan.OuterRadius(s, th, t.wallThicknessMm) + 2.0) * scan.RadialDirection(s, th);
          EXPECT_LT(std::hypot(p.x() / ax, p.y() / ay), 1.0) << s;
          EXPECT_GT(p.z(), lo.z() + 5.0);
          EXPECT_LT(p.z(), hi.z() - 5.0);
        }
      // The closed ends (hemispheric caps) too.
      for (double u : {0.0, scan.centerline.Length()}) {
        Eigen::Vector3d T, N, B;
        scan.centerline.Frame(u, T, N, B);
        const double s = scan.MaterialS(u);
        const Eigen::Vector3d tip = scan.centerline.Point(u) + (u == 0.0 ? -1.0 : 1.0) * (MaxOuterRadius(scan, s, 3.0) + 2.0) * T;
        EXPECT_GT(tip.z(), lo.z() + 3.0);
        EXPECT_LT(std::hypot(tip.x() / ax, tip.y() / ay), 1.0);
      }
    }
  }
}

TEST(PhantomGeometry, ZeroDeformationGivesTheSupineGeometry) {
  const PhantomOptions o = CoarseOptions(4, 0.0);
  const ColonAnatomy a = MakeAnatomy(o);
  const ScanGeometry sup = MakeScan(a, Posture::Supine, o), pro = MakeScan(a, Posture::Prone, o);
  double worst = 0.0;
  for (double s = 0.0; s <= a.length; s += 3.7)
    for (int k = 0; k < 16; ++k) worst = std::max(worst, (sup.WallPoint(s, 0.4 * k) - pro.WallPoint(s, 0.4 * k)).norm());
  EXPECT_LT(worst, 1e-8);
  EXPECT_EQ(pro.Down().y(), -1.0);  // only gravity differs
  EXPECT_EQ(sup.Down().y(), 1.0);
}

TEST(PhantomGeometry, ProneMovesMobileSegmentsAndKeepsFixedOnes) {
  for (std::uint32_t seed : {1u, 2u, 3u}) {
    const PhantomOptions o = CoarseOptions(seed, 1.0);
    const ColonAnatomy a = MakeAnatomy(o);
    const ScanGeometry sup = MakeScan(a, Posture::Supine, o), pro = MakeScan(a, Posture::Prone, o);
    std::array<double, 5> maxMove{};
    for (double s = 0.0; s <= a.length; s += 2.0) {
      const int g = a.SegmentOf(s);
      maxMove[g] = std::max(maxMove[g], (sup.CenterPoint(s) - pro.CenterPoint(s)).norm());
    }
    EXPECT_GT(maxMove[kTransverse], 20.0) << seed;
    EXPECT_GT(maxMove[kSigmoid], 15.0) << seed;
    // Fixed segments: the material slides a little along the centreline, the tube barely moves.
    for (int g : {kAscending, kDescending, kRectum}) EXPECT_LT(maxMove[g], 0.6 * std::max(maxMove[1], maxMove[3])) << g;
    // Longitudinal stretch: local within about +-15-25 %, total length within 5 %.
    double lo = 10, hi = 0;
    for (double s = 0.0; s <= a.length; s += 1.0) lo = std::min(lo, pro.Stretch(s)), hi = std::max(hi, pro.Stretch(s));
    EXPECT_GT(lo, 0.75);
    EXPECT_LT(hi, 1.3);
    EXPECT_GT(hi - lo, 0.15);  // there is stretch
    EXPECT_NEAR(pro.centerline.Length() / sup.centerline.Length(), 1.0, 0.05);
    // Torsion: tens of degrees in the mobile segments relative to the fixed ones.
    double maxTwist = 0.0;
    for (double s = a.flexureS[kHepatic]; s < a.flexureS[kSplenic]; s += 2.0)
      maxTwist = std::max(maxTwist, std::fabs(pro.Twist(s) - pro.Twist(a.flexureS[kHepatic])));
    EXPECT_GT(maxTwist, 15.0 * kPi / 180.0);
  }
}

TEST(PhantomGeometry, LocatorRecoversMaterialCoordinatesOfWallPoints) {
  const PhantomOptions o = CoarseOptions(5, 1.0);
  const ColonAnatomy a = MakeAnatomy(o);
  for (Posture posture : {Posture::Supine, Posture::Prone}) {
    const ScanGeometry scan = MakeScan(a, posture, o);
    const TubeLocator tube(scan, 3.0, 2.0);
    for (double s = 1.0; s < a.length - 1.0; s += 13.3) {
      const double th = std::fmod(s * 0.37, 2 * kPi);
      const TubeSample q = tube.Query(scan.WallPoint(s, th));
      ASSERT_TRUE(q.near) << s;
      EXPECT_NEAR(q.s, s, 1e-5);
      EXPECT_NEAR(AngleDifference(q.theta, th), 0.0, 1e-5);
      EXPECT_NEAR(q.innerDistance, 0.0, 1e-5);
      // Slightly inside is lumen, outside the wall is not.
      const Eigen::Vector3d d = scan.RadialDirection(s, th);
      EXPECT_TRUE(tube.IsLumen(scan.WallPoint(s, th) - 0.3 * d));
      EXPECT_FALSE(tube.IsLumen(scan.WallPoint(s, th) + 0.3 * d));
    }
  }
}
