#pragma once
// Monotone alignment of two sampled sequences (dynamic time warping), libigl style: Eigen in
// and out. Used to carry positions along one colon onto another curve through the same colon
// (RealColon/MidlineAlignment.h) and to align the supine and prone centrelines for the joint
// choice of flexures (Landmarks/JointFlexures.h).
//
// Cost of matching sample i of a with sample j of b: the Euclidean distance of their feature
// rows. Steps (1,1), (1,0), (0,1); a straight (non-diagonal) step costs stepPenalty more, so
// where the features do not tell samples apart the path keeps to the diagonal. Optionally the
// path stays within a band around the proportional diagonal (|i/(m-1) - j/(n-1)| <= band).
#include <Eigen/Core>

namespace colonmap::analysis {

struct WarpingOptions {
  double stepPenalty = 0.0;  // extra cost of a (1,0) or (0,1) step
  double band = 1.0;         // largest |i/(m-1) - j/(n-1)| on the path (1: no band)
};

struct Warping {
  // For every sample i of a, the mean index of the samples of b matched to it (fractional).
  Eigen::VectorXd matchedInB;
  // For every sample j of b, the mean index of the samples of a matched to it.
  Eigen::VectorXd matchedInA;
  double cost = 0.0;  // total cost of the path
  int length = 0;     // number of matched pairs
};

// a: m x k features, b: n x k features (m, n >= 1). Throws colonmap::Error on empty input or
// different feature widths.
Warping WarpSequences(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const WarpingOptions& options = {});

}  // namespace colonmap::analysis
