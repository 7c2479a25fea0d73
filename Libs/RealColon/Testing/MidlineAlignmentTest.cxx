// Ordered alignment of a midline to a curve whose loops pass close to each other.
#include "RealColon/MidlineAlignment.h"
#include "TestShapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::realcolon {
namespace {

// A helix of radius 30 mm rising `pitch` mm per turn, `turns` turns, sampled every ~1 mm.
Eigen::MatrixXd Helix(double pitch, double turns, double dz) {
  const int n = static_cast<int>(2 * M_PI * 30.0 * turns);
  Eigen::MatrixXd P(n + 1, 3);
  for (int i = 0; i <= n; ++i) {
    const double t = 2 * M_PI * turns * i / n;
    P.row(i) << 30.0 * std::cos(t), 30.0 * std::sin(t), pitch * t / (2 * M_PI) + dz;
  }
  return P;
}

TEST(MidlineAlignment, LandmarksKeepTheirPlaceWhereTheNearestPointJumpsALoop) {
  // Turns 3 mm apart; the reference midline runs 2 mm above the curve, so a point of the
  // reference is nearer the next turn (1 mm) than its own (2 mm).
  const Eigen::MatrixXd curve = Helix(3.0, 2.5, 0.0), reference = Helix(3.0, 2.5, 2.0);
  Eigen::VectorXd arcs(4);
  arcs << 60.0, 200.0, 330.0, 420.0;
  const Eigen::VectorXd matched = AlignAlongCurve(reference, curve, arcs);
  const double perArc = 1.0;  // both helices have the same arc length per turn
  double worstNearest = 0.0;
  for (Eigen::Index k = 0; k < arcs.size(); ++k) {
    EXPECT_NEAR(matched(k), arcs(k) * perArc, 3.0) << "landmark " << k;
    // The nearest-point projection of the same landmark.
    Eigen::Index i = static_cast<Eigen::Index>(std::lround(arcs(k)));
    const double nearest = testing::NearestArc(curve, reference.row(std::min(i, reference.rows() - 1)).transpose());
    worstNearest = std::max(worstNearest, std::fabs(nearest - arcs(k)));
  }
  EXPECT_GT(worstNearest, 100.0);  // a whole turn (188 mm) off: why the alignment is ordered
}

}  // namespace
}  // namespace colonmap::realcolon
