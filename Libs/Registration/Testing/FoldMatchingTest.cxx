// Graph-cut fold segmentation, taenia lines, spectral fold matching and the per-vertex
// uncertainty, each on a known answer.
#include "Core/Error.h"
#include "Registration/FeatureMatching.h"
#include "Registration/FoldGraphCut.h"
#include "Registration/FoldFeatures.h"
#include "Registration/RegistrationUncertainty.h"

#include "CylinderSegment.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace colonmap::registration;

namespace {

// A band of rows 10..13 (all columns, so it crosses the periodic seam) at curvature 1, background
// 0 with deterministic "noise" spikes at isolated pixels (value 1.2, one pixel each).
std::vector<float> BandImage(int rows, int cols, std::vector<unsigned char>* truth) {
  std::vector<float> im(static_cast<std::size_t>(rows) * cols, 0.0f);
  truth->assign(im.size(), 0);
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < cols; ++i) {
      const std::size_t p = static_cast<std::size_t>(j) * cols + i;
      // background texture: small smooth variation so the MAD is not zero
      im[p] = 0.05f * static_cast<float>(std::sin(0.7 * i + 1.3 * j));
      if (j >= 10 && j <= 13) {
        im[p] = 1.0f;
        (*truth)[p] = 1;
      }
    }
  for (int j = 25; j < rows; j += 7)
    for (int i = 3; i < cols; i += 9) im[static_cast<std::size_t>(j) * cols + i] = 1.2f;
  return im;
}

}  // namespace

TEST(FoldGraphCut, KeepsTheBandAndDropsIsolatedSpikes) {
  const int rows = 60, cols = 40;
  std::vector<unsigned char> truth;
  const std::vector<float> im = BandImage(rows, cols, &truth);
  GraphCutOptions o;
  o.quantile = 0.85;  // below the band's share of the image (4/60) the threshold sits in the background
  o.smoothness = 0.0;
  const FoldMask plain = SegmentFoldsByGraphCut(im, rows, cols, true, o);
  long spikesPlain = 0;
  for (std::size_t p = 0; p < truth.size(); ++p) spikesPlain += plain.fold[p] && !truth[p];
  EXPECT_GT(spikesPlain, 10);  // the threshold alone keeps every spike (and some texture)
  o.smoothness = 0.5;
  const FoldMask cut = SegmentFoldsByGraphCut(im, rows, cols, true, o);
  long wrong = 0;
  for (std::size_t p = 0; p < truth.size(); ++p) wrong += cut.fold[p] != truth[p];
  EXPECT_EQ(wrong, 0);
  EXPECT_THROW(SegmentFoldsByGraphCut(im, rows, cols + 1, true, o), colonmap::Error);
}

TEST(FoldFeatures, TaeniaPhaseFindsTheGapsBetweenSectors) {
  const int rows = 30, cols = 90;
  // Folds fill each of the three sectors except 4 columns centred on the taeniae at 0.2 + k/3.
  std::vector<unsigned char> fold(static_cast<std::size_t>(rows) * cols, 0);
  for (int j = 0; j < rows; j += 3)
    for (int i = 0; i < cols; ++i) {
      const double u = (i + 0.5) / cols;
      double d = std::fmod(u - 0.2 + 1.0, 1.0 / 3);
      d = std::min(d, 1.0 / 3 - d);
      if (d > 0.025) fold[static_cast<std::size_t>(j) * cols + i] = 1;
    }
  double phase = TaeniaPhase(fold, rows, cols, 1.0);
  phase = std::fmod(phase, 1.0 / 3);
  EXPECT_NEAR(phase, 0.2, 1.5 / cols);
}

namespace {

FoldFeature Fold(double u, double v) {
  FoldFeature f;
  f.centroid = {u, v};
  f.ends[0] = {u - 0.1, v};
  f.ends[1] = {u + 0.1, v};
  f.halfLength = 0.1;
  f.areaMm2 = 60;
  f.meanCurvature = 0.1;
  f.taeniaDistance = 0.0;
  return f;
}

}  // namespace

TEST(FeatureMatching, SpectralFollowsTheNeighboursWhereGreedyTakesTheNearestDecoy) {
  // Supine folds on a grid; the prone ones are displaced by (0, 0.05) everywhere. For supine fold
  // 4 there is also a decoy prone fold right at its predicted position (displacement 0), nearer
  // than its true partner; its neighbours all say 0.05.
  std::vector<FoldFeature> supine, prone;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      supine.push_back(Fold(0.2 + 0.3 * i, 0.3 + 0.15 * j));
      prone.push_back(Fold(0.2 + 0.3 * i, 0.35 + 0.15 * j));
    }
  prone.push_back(Fold(0.5, 0.45 - 0.002));  // decoy for supine 4 (at (0.5, 0.45))
  Eigen::MatrixXd predicted(supine.size(), 2);
  for (std::size_t i = 0; i < supine.size(); ++i) predicted.row(i) = supine[i].centroid.transpose();
  MatchOptions o;
  o.searchRadius = 0.08;
  o.tolerance = 1.0;  // no consistency check: compare the assignments themselves
  o.method = MatchingMethod::Greedy;
  const std::vector<FeatureMatch> greedy = MatchFolds(supine, prone, predicted, 1.0, o);
  o.method = MatchingMethod::Spectral;
  const std::vector<FeatureMatch> spectral = MatchFolds(supine, prone, predicted, 1.0, o);
  auto partnerOf = [](const std::vector<FeatureMatch>& m, int s) {
    for (const FeatureMatch& x : m)
      if (x.supine == s) return x.prone;
    return -1;
  };
  EXPECT_EQ(partnerOf(greedy, 4), 9);    // the decoy
  EXPECT_EQ(partnerOf(spectral, 4), 4);  // the partner the neighbours agree with
  for (int s = 0; s < 9; ++s) EXPECT_EQ(partnerOf(spectral, s), s);
}

TEST(FeatureMatching, SpectralLeavesAnUnsupportedFoldUnmatched) {
  // Folds displaced by (0, 0.05); supine fold 4's true partner is missing and its only candidate
  // is a prone fold whose displacement contradicts all its neighbours.
  std::vector<FoldFeature> supine, prone;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      supine.push_back(Fold(0.2 + 0.3 * i, 0.3 + 0.15 * j));
      if (!(i == 1 && j == 1)) prone.push_back(Fold(0.2 + 0.3 * i, 0.35 + 0.15 * j));
    }
  prone.push_back(Fold(0.5 + 0.06, 0.45 - 0.03));
  Eigen::MatrixXd predicted(supine.size(), 2);
  for (std::size_t i = 0; i < supine.size(); ++i) predicted.row(i) = supine[i].centroid.transpose();
  MatchOptions o;
  o.searchRadius = 0.08;
  o.tolerance = 1.0;
  const std::vector<FeatureMatch> m = MatchFolds(supine, prone, predicted, 1.0, o);
  EXPECT_EQ(m.size(), 8u);
  for (const FeatureMatch& x : m) EXPECT_NE(x.supine, 4);
}

TEST(RegistrationUncertainty, GrowsAwayFromTheMatchesAndNearAnInconsistentOne) {
  // A flat strip 1 x 2 (period 1) on a cylinder of circumference 100 mm: 1 flat unit = 100 mm.
  const int nu = 40, nv = 80;
  const FlatSegment s = colonmap::registration::testing::CylinderSegment(nu, nv, 2.0);
  std::vector<ConstraintPoint> cs;
  int g = 0;
  for (double v = 0.25; v < 1.0; v += 0.25)
    for (double u = 0.125; u < 1.0; u += 0.25) cs.push_back({{u, v}, {0.01, 0.0}, g++});
  const Eigen::VectorXd K = Eigen::VectorXd::Ones(s.F.rows());
  const Eigen::MatrixXd h = Eigen::MatrixXd::Zero(s.uv.rows(), 2);
  const VertexUncertainty smooth = EstimateUncertainty(s, h, K, cs, SegmentEvidence{});
  EXPECT_NEAR(smooth.mmPerFlatUnit, 100.0, 1.0);
  EXPECT_LT(smooth.components.loo.maxCoeff(), 1e-6);  // equal displacements predict each other
  // Vertex at (0.125, 0.25) is a constraint; vertex at (0.125, 2.0) is 1.25 units (125 mm) from the nearest.
  const int atMatch = 10 * (nu + 1) + 5, far = nv * (nu + 1) + 5;
  EXPECT_NEAR(smooth.components.nearMm(atMatch), 0.0, 1e-9);
  EXPECT_NEAR(smooth.components.nearMm(far), 125.0, 1.5);
  EXPECT_GT(smooth.median(far), smooth.median(atMatch));
  EXPECT_GT(smooth.bound90(far), smooth.bound90(atMatch));
  EXPECT_TRUE((smooth.bound90.array() >= smooth.median.array()).all());  // a 90% bound is never below the median
  // One constraint disagreeing with its neighbours by 0.05 (5 mm): its leave-one-out residual is
  // about 5 mm (shared, by the weighting, with its neighbours), and the uncertainty there rises.
  cs[5].displacement = {0.06, 0.0};
  const VertexUncertainty rough = EstimateUncertainty(s, h, K, cs, SegmentEvidence{});
  const int at5 = 20 * (nu + 1) + 15;  // (0.375, 0.5): constraint 5
  EXPECT_GT(rough.components.loo(at5), 1.5);
  EXPECT_GT(rough.median(at5), smooth.median(at5));
}
