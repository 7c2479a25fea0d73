// The curvature-image alignment (initial map of the Harmonic method) and the local flip repair,
// on known answers. Alignment: a cylinder whose tissue carries irregular folds (bumps of
// MeanCurvature at pseudo-random places); the prone scan is the same tissue moved by a known map
// T(u, v) = (u + 0.1 + 0.03 sin(pi v / L), v + 0.08 sin(pi v / L)): a shift around the colon that
// varies along it and an uneven stretch along it, zero at the ends. The warp must follow T far
// better than the affine map does, and stay one-to-one.
#include "Core/Cancel.h"
#include "Registration/CurvatureAlignment.h"
#include "Registration/FeatureMatching.h"
#include "Registration/FlipRepair.h"

#include "CylinderSegment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace colonmap;
using namespace colonmap::registration;

namespace {

constexpr double kL = 3.0;

FlatSegment Grid(int nu, int nv) { return registration::testing::CylinderSegment(nu, nv, kL); }

struct Bump {
  double u, v;
};

// Irregular folds: a fixed linear congruential sequence (deterministic, no library RNG state).
std::vector<Bump> Bumps() {
  std::vector<Bump> b;
  unsigned long x = 12345;
  auto next = [&] {
    x = (1103515245UL * x + 12345UL) % 2147483648UL;
    return static_cast<double>(x) / 2147483648.0;
  };
  for (double v = 0.15; v < kL - 0.1; v += 0.06 + 0.08 * next()) b.push_back({next(), v});
  return b;
}

double Tissue(const std::vector<Bump>& bumps, double u, double v) {
  double h = 0;
  for (const Bump& b : bumps) {
    double du = u - b.u;
    du -= std::round(du);
    const double dv = v - b.v;
    h += std::exp(-(du * du) / (2 * 0.06 * 0.06) - (dv * dv) / (2 * 0.015 * 0.015));
  }
  return h;
}

Eigen::Vector2d T(const Eigen::Vector2d& p) {
  const double s = std::sin(M_PI * p.y() / kL);
  return {p.x() + 0.1 + 0.03 * s, p.y() + 0.08 * s};
}

}  // namespace

TEST(CurvatureAlignment, FollowsAKnownStretchAndVaryingShift) {
  const FlatSegment supine = Grid(96, 288), prone = Grid(96, 288);
  const std::vector<Bump> bumps = Bumps();
  Eigen::VectorXd Hs(supine.uv.rows()), Hp(prone.uv.rows());
  for (Eigen::Index i = 0; i < supine.uv.rows(); ++i) Hs(i) = Tissue(bumps, supine.uv(i, 0), supine.uv(i, 1));
  for (Eigen::Index i = 0; i < prone.uv.rows(); ++i) {
    // The tissue at prone (u', v'): invert T (Newton on v, then u).
    const double vp = prone.uv(i, 1);
    double v = vp;
    for (int it = 0; it < 20; ++it)
      v -= (v + 0.08 * std::sin(M_PI * v / kL) - vp) / (1 + 0.08 * M_PI / kL * std::cos(M_PI * v / kL));
    Hp(i) = Tissue(bumps, prone.uv(i, 0) - 0.1 - 0.03 * std::sin(M_PI * v / kL), v);
  }
  NullProgress progress;
  const CurvatureWarp w = AlignCurvatureImages(supine, Hs, prone, Hp, AlignmentOptions{}, progress);
  ASSERT_TRUE(w.valid);
  for (std::size_t k = 1; k < w.proneV.size(); ++k) EXPECT_GT(w.proneV[k], w.proneV[k - 1]);
  double errWarp = 0, errAffine = 0;
  int n = 0;
  for (Eigen::Index i = 0; i < supine.uv.rows(); i += 7, ++n) {
    const Eigen::Vector2d p = supine.uv.row(i).transpose(), truth = T(p);
    errWarp += PeriodicDifference(w.Apply(p), truth, 1.0).norm();
    errAffine += PeriodicDifference(p, truth, 1.0).norm();  // the affine map is the identity here
  }
  errWarp /= n;
  errAffine /= n;
  std::printf("alignment: mean flat error %.4f (affine %.4f), mean shift %.3f (true mean %.3f)\n", errWarp, errAffine,
              w.MeanShift(), 0.1 + 0.03 * 2 / M_PI);
  EXPECT_LT(errWarp, 0.25 * errAffine);
  EXPECT_NEAR(w.MeanShift(), 0.1 + 0.03 * 2 / M_PI, 0.02);
  EXPECT_GT(w.pathCorrelation, w.affineCorrelation);
}

TEST(FlipRepair, UntanglesAReversedPatchAndKeepsTheRest) {
  FlatSegment s = Grid(20, 20);
  Eigen::MatrixXd image = s.uv;
  const int centre = 10 * 21 + 10;
  image.row(centre) += Eigen::RowVector2d(0.09, 0.2);  // folds the faces around the centre vertex
  auto reversed = [&](const Eigen::MatrixXd& uv) {
    std::vector<Eigen::Index> bad;
    for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
      const Eigen::Vector2d a = uv.row(s.F(f, 0)), b = uv.row(s.F(f, 1)), c = uv.row(s.F(f, 2));
      if ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x() <= 0) bad.push_back(f);
    }
    return bad;
  };
  const std::vector<Eigen::Index> bad = reversed(image);
  ASSERT_FALSE(bad.empty());
  const Eigen::MatrixXd before = image;
  const int moved = RelaxAroundFaces(image, s.F, bad, 1);
  EXPECT_GT(moved, 0);
  EXPECT_TRUE(reversed(image).empty());
  // On a regular grid the uniform Laplacian puts the centre back where it was.
  EXPECT_LT((image.row(centre) - s.uv.row(centre)).norm(), 1e-3);
  int changed = 0;
  for (Eigen::Index i = 0; i < image.rows(); ++i) changed += (image.row(i) - before.row(i)).norm() > 0;
  EXPECT_LE(changed, moved);
}
