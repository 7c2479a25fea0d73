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

// The known pair: supine tissue on the grid, prone the same tissue moved by T.
struct KnownPair {
  FlatSegment supine = Grid(96, 288), prone = Grid(96, 288);
  Eigen::VectorXd Hs, Hp;
  KnownPair() {
    const std::vector<Bump> bumps = Bumps();
    Hs.resize(supine.uv.rows());
    Hp.resize(prone.uv.rows());
    for (Eigen::Index i = 0; i < supine.uv.rows(); ++i) Hs(i) = Tissue(bumps, supine.uv(i, 0), supine.uv(i, 1));
    for (Eigen::Index i = 0; i < prone.uv.rows(); ++i) {
      // The tissue at prone (u', v'): invert T (Newton on v, then u).
      const double vp = prone.uv(i, 1);
      double v = vp;
      for (int it = 0; it < 20; ++it)
        v -= (v + 0.08 * std::sin(M_PI * v / kL) - vp) / (1 + 0.08 * M_PI / kL * std::cos(M_PI * v / kL));
      Hp(i) = Tissue(bumps, prone.uv(i, 0) - 0.1 - 0.03 * std::sin(M_PI * v / kL), v);
    }
  }
};

double Area(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

// Adds thin triangles to the supine segment (three new vertices each, nearly on a line slanted
// along the colon, both slants, counter-clockwise), of area relArea times the mean face's, as the
// flattening leaves where a face is almost degenerate. Any bent map reverses some of them.
void AddThinFaces(FlatSegment& s, Eigen::VectorXd& H, double relArea) {
  const double mean = 1.0 * kL / s.F.rows();
  std::vector<Eigen::Vector2d> uv;
  for (double v0 = 0.3; v0 < kL - 0.4; v0 += 0.25)
    for (const double b : {0.05, -0.05}) {
      const Eigen::Vector2d p0(0.3, v0 + (b < 0 ? 0.1 : 0.0)), d(0.02, b);
      const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()).normalized();
      const double eps = 2 * relArea * mean / (2 * d.norm());  // area = |2d| eps / 2
      Eigen::Vector2d p1 = p0 + d, p2 = p0 + 2 * d + eps * n;
      if (Area(p0, p1, p2) < 0) std::swap(p1, p2);
      for (const auto& p : {p0, p1, p2}) uv.push_back(p);
    }
  const Eigen::Index n0 = s.uv.rows(), f0 = s.F.rows(), added = static_cast<Eigen::Index>(uv.size());
  s.uv.conservativeResize(n0 + added, 2);
  s.position.conservativeResize(n0 + added, 3);
  H.conservativeResize(n0 + added);
  s.F.conservativeResize(f0 + added / 3, 3);
  for (Eigen::Index k = 0; k < added; ++k) {
    s.uv.row(n0 + k) = uv[static_cast<std::size_t>(k)].transpose();
    s.position.row(n0 + k).setZero();
    H(n0 + k) = 0.0;
  }
  for (Eigen::Index f = 0; f < added / 3; ++f) s.F.row(f0 + f) << n0 + 3 * f, n0 + 3 * f + 1, n0 + 3 * f + 2;
}

// How many of the faces from `first` on a map reverses.
int Reversed(const FlatSegment& s, const Eigen::MatrixXd& image, Eigen::Index first) {
  int n = 0;
  for (Eigen::Index f = first; f < s.F.rows(); ++f) {
    const auto at = [&](const Eigen::MatrixXd& m, int k) { return Eigen::Vector2d(m.row(s.F(f, k)).transpose()); };
    if (Area(at(image, 0), at(image, 1), at(image, 2)) <= 0) ++n;
  }
  return n;
}

}  // namespace

TEST(CurvatureAlignment, FollowsAKnownStretchAndVaryingShift) {
  KnownPair pair;
  const FlatSegment& supine = pair.supine;
  const FlatSegment& prone = pair.prone;
  const Eigen::VectorXd &Hs = pair.Hs, &Hp = pair.Hp;
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

// Slivers (area 1e-12 of the mean face's: rounding decides their orientation) do not veto the
// warp: it is still the full warp, though it reverses some of them.
TEST(CurvatureAlignment, SliversDoNotVetoTheWarp) {
  KnownPair pair;
  const Eigen::Index first = pair.supine.F.rows();
  AddThinFaces(pair.supine, pair.Hs, 1e-12);
  NullProgress progress;
  const CurvatureWarp w = AlignCurvatureImages(pair.supine, pair.Hs, pair.prone, pair.Hp, AlignmentOptions{}, progress);
  ASSERT_TRUE(w.valid);
  EXPECT_FALSE(w.shiftOnly);
  EXPECT_GT(Reversed(pair.supine, w.Apply(pair.supine.uv), first), 0) << "no sliver reversed: the test shows nothing";
  EXPECT_EQ(Reversed(pair.supine, w.Apply(pair.supine.uv), 0) - Reversed(pair.supine, w.Apply(pair.supine.uv), first), 0);
}

// Thin faces that are real (1e-6 of the mean face) and reversed by every smoothing leave the
// path's mean shift on the affine length map: one-to-one, and the shift around the colon kept.
TEST(CurvatureAlignment, ThinFacesReversedByEverySmoothingLeaveTheMeanShift) {
  KnownPair pair;
  AddThinFaces(pair.supine, pair.Hs, 1e-6);
  NullProgress progress;
  const CurvatureWarp w = AlignCurvatureImages(pair.supine, pair.Hs, pair.prone, pair.Hp, AlignmentOptions{}, progress);
  ASSERT_TRUE(w.valid);
  ASSERT_TRUE(w.shiftOnly);
  EXPECT_EQ(Reversed(pair.supine, w.Apply(pair.supine.uv), 0), 0);
  EXPECT_NEAR(w.MeanShift(), 0.1 + 0.03 * 2 / M_PI, 0.02);
  // A rotation of the rectangle on the affine length map: W(p) - (p.u, scale p.v) is one constant.
  const Eigen::Vector2d a = w.Apply(Eigen::Vector2d(0.2, 0.5)), b = w.Apply(Eigen::Vector2d(0.7, 2.5));
  EXPECT_NEAR(a.x() - 0.2, b.x() - 0.7, 1e-12);
  EXPECT_NEAR((b.y() - a.y()) / 2.0, w.scale, 1e-9);
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
