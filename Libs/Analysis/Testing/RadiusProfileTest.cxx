// Known-answer tests of the tube analysis: exact nearest midline points, the radius of a tube
// of known radius along a bent (helical) midline, and the fold spacing of tubes with periodic
// narrowings, all around and staggered between sectors as the phantom's haustra are.
#include "Core/TimeLimit.h"
#include <Analysis/FoldPositions.h>
#include <Analysis/MidlineProjection.h>
#include <Analysis/RadiusProfile.h>
#include <Analysis/SampleSurface.h>

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <chrono>
#include <cmath>
#include <functional>
#include <random>

using namespace colonmap::analysis;

namespace {
constexpr double kPi = 3.14159265358979323846;

// Helix x = A cos t, y = A sin t, z = C t: curvature radius (A^2 + C^2) / A = 116 mm, far above
// the tube radii used here; pitch 2 pi C = 251 mm, so the tube never meets itself.
constexpr double kA = 100.0, kC = 40.0;
const double kSpeed = std::sqrt(kA * kA + kC * kC);  // ds/dt

struct Frame {
  Eigen::Vector3d c, T, N, B;
};
Frame HelixAt(double s) {
  const double t = s / kSpeed;
  Frame f;
  f.c = Eigen::Vector3d(kA * std::cos(t), kA * std::sin(t), kC * t);
  f.T = Eigen::Vector3d(-kA * std::sin(t), kA * std::cos(t), kC) / kSpeed;
  f.N = Eigen::Vector3d(-std::cos(t), -std::sin(t), 0.0);  // Frenet normal (twists against the RMF)
  f.B = f.T.cross(f.N);
  return f;
}

Eigen::MatrixXd HelixMidline(double length, double step) {
  const int n = static_cast<int>(std::round(length / step)) + 1;
  Eigen::MatrixXd m(n, 3);
  for (int i = 0; i < n; ++i) m.row(i) = HelixAt(length * i / (n - 1)).c.transpose();
  return m;
}

// Tube wall as a grid mesh: rows along s (step ds), `around` points per ring, radius r(s, theta).
void TubeMesh(double length, double ds, int around, const std::function<double(double, double)>& r,
              Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  const int rings = static_cast<int>(std::round(length / ds)) + 1;
  V.resize(rings * around, 3);
  F.resize(2 * (rings - 1) * around, 3);
  for (int i = 0; i < rings; ++i) {
    const double s = length * i / (rings - 1);
    const Frame f = HelixAt(s);
    for (int j = 0; j < around; ++j) {
      const double th = 2.0 * kPi * j / around;
      V.row(i * around + j) = (f.c + r(s, th) * (std::cos(th) * f.N + std::sin(th) * f.B)).transpose();
    }
  }
  int k = 0;
  for (int i = 0; i + 1 < rings; ++i)
    for (int j = 0; j < around; ++j) {
      const int a = i * around + j, b = i * around + (j + 1) % around, c = a + around, d = b + around;
      F.row(k++) << a, b, d;
      F.row(k++) << a, d, c;
    }
}
}  // namespace

TEST(MidlineProjection, ExactNearestPointAgainstBruteForce) {
  const Eigen::MatrixXd mid = HelixMidline(500.0, 1.0);
  const Eigen::VectorXd cum = ArcLength(mid);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::MatrixXd P(2000, 3);
  for (int i = 0; i < P.rows(); ++i) {
    const Frame f = HelixAt(250.0 + 250.0 * u(rng));
    P.row(i) = (f.c + Eigen::Vector3d(u(rng), u(rng), u(rng)) * 60.0).transpose();
  }
  ProjectionOptions o;
  o.excludeBeyondEnds = false;
  const MidlineProjection p = ProjectToMidline(P, mid, o);
  for (int i = 0; i < P.rows(); ++i) {
    double best = 1e300, bestArc = 0.0;
    for (int s = 0; s + 1 < mid.rows(); ++s) {
      const Eigen::Vector3d a = mid.row(s).transpose(), e = mid.row(s + 1).transpose() - a;
      const double t = std::clamp((P.row(i).transpose() - a).dot(e) / e.squaredNorm(), 0.0, 1.0);
      const double d = (a + t * e - P.row(i).transpose()).norm();
      if (d < best) best = d, bestArc = cum(s) + t * (cum(s + 1) - cum(s));
    }
    ASSERT_NEAR(p.distance(i), best, 1e-9) << i;
    if (std::fabs(p.distance(i) - best) < 1e-12) {
      EXPECT_NEAR(p.arc(i), bestArc, 1e-6);
    }
  }
}

TEST(MidlineProjection, RotationMinimisingAnglesAndEndExclusion) {
  // Straight midline along x: the frame is constant, angles are those of the points.
  Eigen::MatrixXd mid(11, 3);
  for (int i = 0; i < 11; ++i) mid.row(i) << 10.0 * i, 0, 0;
  Eigen::MatrixXd P(4, 3);
  P << 50, 0, 5,    // at arc 50, in the (N, B) plane
      50, 5, 0,     //
      -3, 1, 0,     // before the start: excluded
      104, 0, 2;    // after the end: excluded
  ProjectionOptions o;
  o.normalHint = Eigen::Vector3d(0, 1, 0);  // N = +y, B = x cross y = +z
  const MidlineProjection p = ProjectToMidline(P, mid, o);
  EXPECT_NEAR(p.arc(0), 50.0, 1e-12);
  EXPECT_NEAR(p.angle(0), 0.5 * kPi, 1e-12);
  EXPECT_NEAR(p.angle(1), 0.0, 1e-12);
  EXPECT_TRUE(std::isnan(p.arc(2)));
  EXPECT_TRUE(std::isnan(p.arc(3)));
  EXPECT_NEAR(p.distance(3), std::sqrt(16.0 + 4.0), 1e-12);
  // A full turn of the frame along a closed-form helix stays rotation minimising: the
  // transported normal changes by no more than the discrete turning per segment.
  Eigen::MatrixXd T, N, B;
  SegmentFrames(HelixMidline(500.0, 1.0), T, N, B);
  for (Eigen::Index i = 0; i < T.rows(); ++i) {
    EXPECT_NEAR(T.row(i).dot(N.row(i)), 0.0, 1e-9);
    EXPECT_NEAR(N.row(i).norm(), 1.0, 1e-9);
    if (i > 0) {
      EXPECT_NEAR(N.row(i).dot(T.row(i - 1)), -T.row(i).dot(N.row(i - 1)), 1e-6);  // no spin about T
    }
  }
}

TEST(RadiusProfile, TubeOfKnownRadiusAlongBentMidline) {
  const double L = 500.0, R = 20.0;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  TubeMesh(L, 1.0, 128, [&](double, double) { return R; }, V, F);
  const Eigen::MatrixXd W = SampleSurface(V, F, 1.0);
  // The sample count matches the area (2 pi R L) within its Poisson spread.
  EXPECT_NEAR(static_cast<double>(W.rows()), 2.0 * kPi * R * L, 4.0 * std::sqrt(2.0 * kPi * R * L));
  const TubeProfile p = RadiusProfile(W, HelixMidline(L, 1.0), 2.0);
  ASSERT_EQ(p.NumberOfBins(), 250);
  EXPECT_EQ(p.sectors, 8);
  // Discretisation: the 128-gon's chords sit up to R (1 - cos(pi / 128)) = 0.006 mm inside.
  for (Eigen::Index k = 0; k < p.NumberOfBins(); ++k) {
    ASSERT_TRUE(std::isfinite(p.radius(k))) << k;
    EXPECT_NEAR(p.radius(k), R, 0.02) << "bin " << k;
    for (int s = 0; s < p.sectors; ++s) EXPECT_NEAR(p.sectorRadius(k, s), R, 0.03);
  }
  const RadiusSummary all = SummarizeRadius(p, 0.0, L);
  EXPECT_NEAR(all.median, R, 0.01);
  EXPECT_EQ(all.bins, 250);
  EXPECT_LT(p.excluded, W.rows() / 1000);
}

TEST(RadiusProfile, TaperedTubeAndSummaries) {
  // Radius 30 -> 15 mm linearly: each bin reports the radius at its centre.
  const double L = 400.0;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  const auto r = [&](double s, double) { return 30.0 - 15.0 * s / L; };
  TubeMesh(L, 0.5, 160, r, V, F);
  const TubeProfile p = RadiusProfile(SampleSurface(V, F, 0.5), HelixMidline(L, 1.0), 4.0);
  for (Eigen::Index k = 0; k < p.NumberOfBins(); ++k) EXPECT_NEAR(p.radius(k), r(p.arc(k), 0), 0.15) << k;
  const RadiusSummary first = SummarizeRadius(p, 0.0, 100.0);
  EXPECT_NEAR(first.median, r(50.0, 0), 0.15);
  EXPECT_EQ(first.bins, 25);
  EXPECT_TRUE(std::isnan(SummarizeRadius(p, 500.0, 600.0).median));
}

TEST(FoldPositions, SinusoidalNarrowingAllAroundGivesItsPeriod) {
  const double L = 500.0, R = 20.0, period = 25.0, depth = 3.0;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.2);  // mesh ripple
  TubeMesh(L, 1.0, 128,
           [&](double s, double) { return R - depth * 0.5 * (1.0 + std::cos(2.0 * kPi * s / period)) + noise(rng); }, V, F);
  const TubeProfile p = RadiusProfile(SampleSurface(V, F, 1.0), HelixMidline(L, 1.0), 1.0);
  for (bool perSector : {false, true}) {
    FoldOptions o;
    o.perSector = perSector;
    const std::vector<FoldMinimum> m = FoldMinima(p, o);
    const FoldSpacingSummary s = FoldSpacing(m, 0.0, L);
    SCOPED_TRACE(perSector ? "per sector" : "all angles");
    EXPECT_NEAR(s.median, period, 1.0);
    EXPECT_NEAR(s.p25, period, 1.5);
    EXPECT_NEAR(s.p75, period, 1.5);
    // Minima at the narrowings s = k period, none missed except at the very ends.
    const int sectors = perSector ? p.sectors : 1;
    EXPECT_GE(static_cast<int>(m.size()), sectors * (static_cast<int>(L / period) - 2));
    EXPECT_LE(static_cast<int>(m.size()), sectors * static_cast<int>(L / period));
    for (const FoldMinimum& f : m) {
      EXPECT_NEAR(std::remainder(f.arc, period), 0.0, 1.5) << f.arc;
      EXPECT_NEAR(f.prominence, depth, 0.8);
    }
  }
  // No narrowing, only ripple: no folds.
  TubeMesh(L, 1.0, 128, [&](double, double) { return R + noise(rng); }, V, F);
  const TubeProfile flat = RadiusProfile(SampleSurface(V, F, 1.0), HelixMidline(L, 1.0), 1.0);
  EXPECT_EQ(FoldMinima(flat).size(), 0u);
}

TEST(FoldPositions, StaggeredSectorFoldsGiveTheSectorSpacing) {
  // Three 120-degree sectors (bounded by "taeniae" fixed in the twisting Frenet frame), each
  // with raised-cosine crescent folds every 27 mm, offset by 9 mm between sectors: folds
  // come every 9 mm around the tube but every 27 mm in a sector, as in the phantom.
  const double L = 600.0, R = 20.0, period = 27.0;
  const auto fold = [&](double s, double th) {
    const int k = std::min(2, static_cast<int>(th / (2.0 * kPi / 3.0)));
    const double phi = th / (2.0 * kPi / 3.0) - k;
    const double taper = std::pow(std::sin(kPi * phi), 2);
    const double x = std::remainder(s - 9.0 * k, period);  // distance to this sector's crest
    const double along = std::fabs(x) < 4.5 ? 0.5 * (1.0 + std::cos(kPi * x / 4.5)) : 0.0;
    return R - 5.0 * taper * along;
  };
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  TubeMesh(L, 0.5, 180, fold, V, F);
  const TubeProfile p = RadiusProfile(SampleSurface(V, F, 1.0), HelixMidline(L, 1.0), 1.0);
  const FoldSpacingSummary s = FoldSpacing(FoldMinima(p), 20.0, L - 20.0);
  EXPECT_NEAR(s.median, period, 1.5);
  EXPECT_GE(s.p25, 0.8 * period);
  // The all-angle median hardly sees folds covering a third of the circumference.
  FoldOptions all;
  all.perSector = false;
  EXPECT_LT(FoldMinima(p, all).size(), 5u);
}

TEST(MidlineProjection, HundredThousandPointsWellUnderASecond) {
  const double L = 1500.0;
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  TubeMesh(L, 1.0, 100, [](double, double) { return 25.0; }, V, F);  // ~150K points
  const Eigen::MatrixXd mid = HelixMidline(L, 1.0);
  const auto t0 = std::chrono::steady_clock::now();
  const TubeProfile p = RadiusProfile(V, mid, 1.0);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("RadiusProfile of %ld points on a %ld-point midline: %.3f s\n", static_cast<long>(V.rows()),
              static_cast<long>(mid.rows()), secs);
  EXPECT_LT(secs, 1.0 * colonmap::kTimeLimitScale);
  EXPECT_NEAR(SummarizeRadius(p, 0.0, L).median, 25.0, 0.05);
}
