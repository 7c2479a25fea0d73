// Unit tests of Libs/Registration on exact answers: point location in a periodic flat strip,
// the affine rectangle map, the cyclic shift of a shifted image, the Beltrami coefficient of a
// known affine 3D map, error statistics.
#include "Core/Error.h"
#include "Registration/ErrorStatistics.h"
#include "Registration/FlatLocator.h"
#include "Registration/RectangleAffine.h"
#include "Registration/SurfaceMap.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <tuple>

#include <cmath>

using namespace colonmap;
using namespace colonmap::registration;

namespace {

// A strip [0, 1] x [0, len] of nu x nv quads, each split in two; u periodic with period 1.
void Strip(int nu, int nv, double len, Eigen::MatrixXd& uv, Eigen::MatrixXi& F) {
  uv.resize((nu + 1) * (nv + 1), 2);
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) uv.row(j * (nu + 1) + i) << double(i) / nu, len * j / nv;
  F.resize(2 * nu * nv, 3);
  int f = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      F.row(f++) << a, b, d;
      F.row(f++) << a, d, c;
    }
}

Eigen::Vector2d At(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, const FlatHit& h) {
  return h.bary(0) * uv.row(F(h.face, 0)).transpose() + h.bary(1) * uv.row(F(h.face, 1)).transpose() +
         h.bary(2) * uv.row(F(h.face, 2)).transpose();
}

}  // namespace

TEST(FlatLocator, FindsInsideOutsideAndPeriodicPoints) {
  Eigen::MatrixXd uv;
  Eigen::MatrixXi F;
  Strip(12, 30, 3.0, uv, F);
  const FlatTriangleLocator loc(uv, F, 1.0);
  for (const Eigen::Vector2d& p : {Eigen::Vector2d(0.31, 1.7), Eigen::Vector2d(0.999, 0.01), Eigen::Vector2d(0.5, 2.5)}) {
    const FlatHit h = loc.Locate(p);
    ASSERT_TRUE(h.inside);
    EXPECT_LT((At(uv, F, h) - p).norm(), 1e-12);
    EXPECT_GE(h.bary.minCoeff(), 0.0);
  }
  // Periodic copies: u = 1.25 and -0.75 are u = 0.25.
  for (double u : {1.25, -0.75, 3.25}) {
    const FlatHit h = loc.Locate(Eigen::Vector2d(u, 1.0));
    ASSERT_TRUE(h.inside);
    EXPECT_LT((At(uv, F, h) - Eigen::Vector2d(0.25, 1.0)).norm(), 1e-12);
  }
  // Beyond the ends: clamped to the nearest point of the strip.
  const FlatHit below = loc.Locate(Eigen::Vector2d(0.4, -0.2));
  EXPECT_FALSE(below.inside);
  EXPECT_NEAR(below.distance, 0.2, 1e-12);
  EXPECT_LT((At(uv, F, below) - Eigen::Vector2d(0.4, 0.0)).norm(), 1e-12);
  const FlatHit above = loc.Locate(Eigen::Vector2d(1.4, 3.5));
  EXPECT_LT((At(uv, F, above) - Eigen::Vector2d(0.4, 3.0)).norm(), 1e-12);
  // Without periodicity a point left of the strip clamps to its left side.
  const FlatTriangleLocator plain(uv, F, 0.0);
  const FlatHit left = plain.Locate(Eigen::Vector2d(-0.3, 1.0));
  EXPECT_FALSE(left.inside);
  EXPECT_LT((At(uv, F, left) - Eigen::Vector2d(0.0, 1.0)).norm(), 1e-12);
}

TEST(FlatLocator, PeriodFromCutCopies) {
  Eigen::MatrixXd uv;
  Eigen::MatrixXi F;
  Strip(8, 4, 1.0, uv, F);
  // Wrap the strip onto a cylinder: u = 0 and u = 1 columns share their 3D positions.
  Eigen::MatrixXd P(uv.rows(), 3);
  for (Eigen::Index i = 0; i < uv.rows(); ++i) {
    const double a = 2 * M_PI * std::fmod(uv(i, 0), 1.0);
    P.row(i) << std::cos(a), std::sin(a), uv(i, 1);
  }
  EXPECT_NEAR(FlatPeriodFromCut(uv, P), 1.0, 1e-12);
}

// A flattening report's width must be the map's own: the cut's period within 1%, or without cut
// copies within a factor 2 of the span of u.
TEST(FlatLocator, ReportedWidthCheckedAgainstTheMap) {
  Eigen::MatrixXd uv;
  Eigen::MatrixXi F;
  Strip(8, 4, 1.0, uv, F);
  Eigen::MatrixXd P(uv.rows(), 3), apart(uv.rows(), 3);
  for (Eigen::Index i = 0; i < uv.rows(); ++i) {
    const double a = 2 * M_PI * std::fmod(uv(i, 0), 1.0);
    P.row(i) << std::cos(a), std::sin(a), uv(i, 1);
    apart.row(i) << uv(i, 0), uv(i, 1), 0.0;  // no two points share a position: no cut copies
  }
  const auto width = [&](std::optional<double> w, const Eigen::MatrixXd& positions) {
    return CheckedFlatPeriod(w, uv, positions, "A", "supine flattening report", "f.json");
  };
  EXPECT_NEAR(width(std::nullopt, P), 1.0, 1e-12);
  EXPECT_EQ(width(1.005, P), 1.005);
  EXPECT_EQ(width(std::nullopt, apart), 0.0);
  EXPECT_EQ(width(1.8, apart), 1.8);
  EXPECT_THROW(width(1.05, P), Error);
  EXPECT_THROW(width(1e4, apart), Error);
  EXPECT_THROW(width(0.4, apart), Error);
  try {
    width(3.0, P);
    ADD_FAILURE() << "a width three times the cut's period was taken";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("supine flattening report 'f.json': gives segment A a flat width of 3"),
              std::string::npos) << e.what();
  }
}

TEST(RectangleAffine, MapsEndsToEndsAndInverts) {
  Eigen::MatrixXd a(2, 2), b(2, 2);
  a << 0, 0.1, 1, 2.1;
  b << 0, 0.0, 1, 3.0;
  const RectangleAffine eta = FitRectangleAffine(a, b, 0.2);
  EXPECT_NEAR(eta.scale, 1.5, 1e-12);
  EXPECT_LT((eta.Apply(Eigen::Vector2d(0.3, 2.1)) - Eigen::Vector2d(0.5, 3.0)).norm(), 1e-12);
  EXPECT_LT((eta.Inverse(eta.Apply(Eigen::Vector2d(0.7, 1.3))) - Eigen::Vector2d(0.7, 1.3)).norm(), 1e-12);
}

TEST(RectangleAffine, CyclicShiftOfAShiftedImage) {
  Volume<float> a, b;
  a.size = b.size = {64, 40, 1};
  a.Allocate();
  b.Allocate();
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 64; ++i) {
      auto f = [&](int x) { return static_cast<float>(std::sin(2 * M_PI * x / 64.0 * 3 + j * 0.3) + (x % 64 == 10 ? 2 : 0)); };
      a.At(i, j, 0) = f(i);
      b.At(i, j, 0) = f((i - 16 + 64) % 64);  // b(x + 16) = a(x): prone u = supine u + 1/4
    }
  const CyclicShift s = CyclicShiftByCorrelation(a, b, 64, 40);
  EXPECT_NEAR(s.shift, 0.25, 1e-9);
  EXPECT_NEAR(s.correlation, 1.0, 1e-6);
  EXPECT_LT(s.correlationAtZero, 0.9);
}

TEST(SurfaceMap, BeltramiOfAKnownAffineMap) {
  // Source: triangles in the plane z = 0; image: stretched by 2 along x and rotated into 3D.
  Eigen::MatrixXd V(4, 3), W(4, 3);
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::MatrixXi F(2, 3);
  F << 0, 1, 2, 0, 2, 3;
  Eigen::Matrix3d R;
  R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (int i = 0; i < 4; ++i) W.row(i) = (R * Eigen::Vector3d(2 * V(i, 0), V(i, 1), 0)).transpose();
  const Eigen::VectorXcd mu = SurfaceMapBeltrami(V, F, W);
  const Eigen::VectorXd K = Dilatation(mu);
  for (int f = 0; f < 2; ++f) {
    EXPECT_NEAR(std::abs(mu(f)), 1.0 / 3.0, 1e-12);  // (2 - 1) / (2 + 1)
    EXPECT_NEAR(K(f), 2.0, 1e-12);
  }
  EXPECT_NEAR(std::abs(SurfaceMapBeltrami(V, F, V)(0)), 0.0, 1e-12);
}

TEST(SurfaceMap, FlatFrameBeltramiGivesTheStretchDirectionWhateverTheCornerOrder) {
  // Flat source grid; image: stretched by 2 along v (along the colon), or along u, then rotated
  // into 3D. theta = arg(mu) / 2 is the stretch direction from the u axis: 90 and 0 degrees,
  // for every face and every order of its corners.
  Eigen::MatrixXd uv(4, 2), V(4, 3), W(4, 3);
  uv << 0, 0, 1, 0, 1, 1, 0, 1;
  V << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Eigen::MatrixXi F(6, 3);
  F << 0, 1, 2, 1, 2, 0, 2, 0, 1, 0, 2, 3, 2, 3, 0, 3, 0, 2;  // two faces, each in 3 rotations
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  for (const auto& [su, sv, theta] : {std::tuple{1.0, 2.0, 90.0}, std::tuple{2.0, 1.0, 0.0}}) {
    for (int i = 0; i < 4; ++i) W.row(i) = (R * Eigen::Vector3d(su * uv(i, 0), sv * uv(i, 1), 0)).transpose();
    const Eigen::VectorXcd mu = FlatFrameBeltrami(V, uv, F, W);
    for (int f = 0; f < F.rows(); ++f) {
      EXPECT_NEAR(std::abs(mu(f)), 1.0 / 3.0, 1e-12);
      const double deg = std::arg(mu(f)) / 2.0 * 180.0 / M_PI;
      EXPECT_NEAR(std::abs(std::remainder(deg - theta, 180.0)), 0.0, 1e-9) << "face " << f;
    }
    // The per-triangle frame gives another angle for each corner order: the reason for this.
    const Eigen::VectorXcd own = SurfaceMapBeltrami(V, F, W);
    EXPECT_GT(std::abs(std::arg(own(0)) - std::arg(own(1))), 0.1);
  }
}

TEST(ErrorStatistics, KnownQuantiles) {
  const ErrorSummary s = SummarizeErrors({4, 1, 3, 2, 10});
  EXPECT_EQ(s.count, 5);
  EXPECT_DOUBLE_EQ(s.mean, 4.0);
  EXPECT_DOUBLE_EQ(s.median, 3.0);
  EXPECT_DOUBLE_EQ(s.p90, 4 + 0.6 * 6);
  EXPECT_DOUBLE_EQ(s.max, 10.0);
  EXPECT_EQ(SummarizeErrors({}).count, 0);
}
