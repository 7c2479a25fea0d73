// Dynamic time warping with known answers: a sequence against itself, against a copy with a
// stretch, the band and the step penalty.
#include "Analysis/DynamicTimeWarping.h"
#include "Core/Error.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::analysis {
namespace {

// A 1-feature sequence with distinct values: f(t) = sin(t / 7) + t / 50.
Eigen::MatrixXd Signal(const Eigen::VectorXd& t) {
  Eigen::MatrixXd f(t.size(), 1);
  for (Eigen::Index i = 0; i < t.size(); ++i) f(i, 0) = std::sin(t(i) / 7.0) + t(i) / 50.0;
  return f;
}

TEST(DynamicTimeWarping, ASequenceMatchesItselfOnTheDiagonal) {
  const Eigen::MatrixXd a = Signal(Eigen::VectorXd::LinSpaced(200, 0.0, 199.0));
  const Warping w = WarpSequences(a, a);
  EXPECT_NEAR(w.cost, 0.0, 1e-12);
  for (Eigen::Index i = 0; i < a.rows(); ++i) EXPECT_DOUBLE_EQ(w.matchedInB(i), static_cast<double>(i));
}

TEST(DynamicTimeWarping, RecoversAStretchedMiddle) {
  // b samples the same signal, its middle third (t in [60, 130]) stretched 1.5 times.
  std::vector<double> tb;
  for (double t = 0.0; t <= 199.0 + 1e-9;) {
    tb.push_back(t);
    t += (t >= 60.0 && t < 130.0) ? 1.0 / 1.5 : 1.0;
  }
  const Eigen::VectorXd tB = Eigen::Map<Eigen::VectorXd>(tb.data(), static_cast<Eigen::Index>(tb.size()));
  const Eigen::MatrixXd a = Signal(Eigen::VectorXd::LinSpaced(200, 0.0, 199.0)), b = Signal(tB);
  const Warping w = WarpSequences(a, b);
  // Sample i of a (t = i) matches the sample of b with the same t.
  for (Eigen::Index i = 5; i < 195; ++i) {
    const double j = w.matchedInB(i);
    const Eigen::Index j0 = static_cast<Eigen::Index>(std::floor(j));
    const double t = tB(j0) + (j - j0) * (tB(std::min<Eigen::Index>(j0 + 1, tB.size() - 1)) - tB(j0));
    EXPECT_NEAR(t, static_cast<double>(i), 1.5) << i;
  }
  // And back.
  for (Eigen::Index j = 5; j + 5 < tB.size(); ++j) EXPECT_NEAR(w.matchedInA(j), tB(j), 1.5) << j;
}

TEST(DynamicTimeWarping, PenaltyKeepsTheDiagonalWhereFeaturesAreFlatAndTheBandHolds) {
  // Constant features: any monotone path costs 0; with a step penalty the diagonal wins.
  const Eigen::MatrixXd a = Eigen::MatrixXd::Zero(100, 2), b = Eigen::MatrixXd::Zero(100, 2);
  WarpingOptions o;
  o.stepPenalty = 0.01;
  const Warping w = WarpSequences(a, b, o);
  for (Eigen::Index i = 0; i < 100; ++i) EXPECT_DOUBLE_EQ(w.matchedInB(i), static_cast<double>(i));
  // A feature that would pull the path far off the diagonal is not reached outside the band.
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(100, 1), d = Eigen::MatrixXd::Zero(100, 1);
  c(20, 0) = 5.0;
  d(80, 0) = 5.0;
  o.band = 0.1;
  const Warping banded = WarpSequences(c, d, o);
  for (Eigen::Index i = 0; i < 100; ++i) EXPECT_LE(std::fabs(banded.matchedInB(i) - static_cast<double>(i)), 10.0 + 1e-9);
  EXPECT_THROW(WarpSequences(Eigen::MatrixXd(0, 1), d), Error);
  EXPECT_THROW(WarpSequences(c, Eigen::MatrixXd::Zero(10, 2)), Error);
}

}  // namespace
}  // namespace colonmap::analysis
