#pragma once
// How alike two flat pictures are (issue 8): the Pearson correlation of two value lists over the
// pixels where both are finite. Used to measure that the registered prone curvature picture
// matches the supine one better than the unregistered one. Eigen in, numbers out.
#include <Eigen/Core>

namespace colonmap::views {

struct Correlation {
  double r = 0.0;    // Pearson correlation; 0 when either side is constant over the pixels used
  long pixels = 0;   // pixels where both values are finite
};

Correlation FlatImageCorrelation(const Eigen::VectorXf& a, const Eigen::VectorXf& b);

}  // namespace colonmap::views
