// The Harmonic method on a known answer: a cylinder (circumference 100 mm, periodic cut) with
// planted folds (Gaussian bumps of MeanCurvature); the prone scan is the same tissue (vertex i is
// vertex i) with its flat v displaced by a smooth known function that vanishes at the ends. The
// affine map cannot follow that displacement; the harmonic correction from matched folds must.
#include "Registration/FoldFeatures.h"
#include "Registration/SegmentRegistration.h"

#include "CylinderSegment.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace colonmap;
using namespace colonmap::registration;

namespace {

constexpr double kLen = 3.0;

FlatSegment Cylinder(int nu, int nv) { return registration::testing::CylinderSegment(nu, nv, kLen); }

// Folds: 3 columns around, every 0.25 along (staggered), elongated around.
Eigen::VectorXd Folds(const Eigen::MatrixXd& uv) {
  Eigen::VectorXd H = Eigen::VectorXd::Zero(uv.rows());
  for (int c = 0; c < 3; ++c)
    for (double v = 0.2; v < kLen - 0.1; v += 0.25) {
      const double u0 = (c + 0.5) / 3 + (std::fmod(v, 0.5) < 0.25 ? 0.03 : -0.03);
      for (Eigen::Index i = 0; i < uv.rows(); ++i) {
        double du = uv(i, 0) - u0;
        du -= std::round(du);
        const double dv = uv(i, 1) - v;
        H(i) += 0.2 * std::exp(-(du * du) / (2 * 0.05 * 0.05) - (dv * dv) / (2 * 0.02 * 0.02));
      }
    }
  return H;
}

double MeanError(const SegmentRegistration& r, const FlatSegment& prone) {
  return (r.forward.position - prone.position).rowwise().norm().mean();
}

}  // namespace

TEST(FoldFeatures, FindsThePlantedFolds) {
  const FlatSegment s = Cylinder(96, 288);
  const std::vector<FoldFeature> folds = DetectFolds(s, Folds(s.uv));
  int planted = 0;
  for (double v = 0.2; v < kLen - 0.1; v += 0.25) planted += 3;
  EXPECT_EQ(static_cast<int>(folds.size()), planted);
  for (const FoldFeature& f : folds) {
    EXPECT_LT(std::fabs(std::sin(f.orientation)), 0.2);  // elongated around the colon
    EXPECT_GT(f.halfLength, 0.02);
  }
}

TEST(HarmonicRegistration, RecoversASmoothDisplacementAlongTheColon) {
  const FlatSegment supine = Cylinder(96, 288);
  FlatSegment prone = supine;
  // The prone tissue slides along the colon by up to 0.06 widths (6 mm), zero at the ends; its
  // 3D positions follow its flat ones (a cylinder again), so vertex i is the same tissue.
  for (Eigen::Index i = 0; i < prone.uv.rows(); ++i) {
    const double v = supine.uv(i, 1);
    prone.uv(i, 1) = v + 0.06 * std::sin(M_PI * v / kLen);
  }
  // Prone positions: the supine cylinder evaluated at the prone flat coordinates.
  for (Eigen::Index i = 0; i < prone.uv.rows(); ++i) prone.position(i, 2) = 100 * prone.uv(i, 1);
  SegmentInput s, p;
  s.flat = supine;
  p.flat = prone;
  s.meanCurvature = Folds(supine.uv);
  p.meanCurvature = s.meanCurvature;  // folds are tissue: they move with it
  s.cutTaenia = p.cutTaenia = "TO";
  NullProgress progress;
  const SegmentRegistration conformal = RegisterSegment(s, p, RegistrationMethod::Conformal, progress);
  const SegmentRegistration harmonic = RegisterSegment(s, p, RegistrationMethod::Harmonic, progress);
  EXPECT_GT(harmonic.matches.size(), harmonic.supineFolds.size() / 2);
  EXPECT_EQ(harmonic.flatFlips + harmonic.surfaceFlips, 0);
  const double ec = MeanError(conformal, prone), eh = MeanError(harmonic, prone);
  std::printf("synthetic: conformal %.3f mm, harmonic %.3f mm, %zu of %zu folds matched\n", ec, eh, harmonic.matches.size(),
              harmonic.supineFolds.size());
  EXPECT_LT(eh, 0.5 * ec);
}
