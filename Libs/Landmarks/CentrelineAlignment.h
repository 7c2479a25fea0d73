#pragma once
// Which place of one scan's centreline is which place of the other's (issue 19): the supine and
// prone centrelines are the same colon, moved and stretched a little (segments by up to about
// 15%), so their directions of travel follow the same sequence of bends. A monotone alignment
// (Analysis/DynamicTimeWarping.h) of the unit directions of travel (chord over +-tangentMm,
// samples every stepMm), kept within a band around proportional arc length and to the diagonal
// where straight stretches look alike.
#include <Eigen/Core>

namespace colonmap::landmarks {

struct CentrelineAlignmentOptions {
  double stepMm = 2.0;
  double tangentMm = 10.0;
  double band = 0.15;         // of the colon's length
  double stepPenalty = 0.05;  // per non-diagonal step (a direction difference of 0.05)
};

class CentrelineAlignment {
 public:
  // a, b: centrelines from the anal end to the cecum (at least two points each).
  CentrelineAlignment(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const CentrelineAlignmentOptions& options = {});
  double AToB(double arcA) const;  // arc length along b matched to arc length arcA along a
  double BToA(double arcB) const;
  double meanCost = 0.0;           // mean direction difference along the path (0 same, 2 opposite)

 private:
  Eigen::VectorXd arcA_, matchedB_, arcB_, matchedA_;  // sample arcs and their matches
};

}  // namespace colonmap::landmarks
