#pragma once
// Piecewise-linear interpolation of a sampled function y(x) (x increasing), constant beyond the
// ends. Eigen in, header only.
#include <Eigen/Core>

#include <algorithm>

namespace colonmap::analysis {

// The knot interval [x(i), x(i+1)] holding v (clamped to the first and last interval).
inline Eigen::Index KnotInterval(const Eigen::VectorXd& x, double v) {
  const Eigen::Index i = (std::upper_bound(x.data(), x.data() + x.size(), v) - x.data()) - 1;
  return std::clamp<Eigen::Index>(i, 0, x.size() - 2);
}

// y at v; x: at least two increasing knots, y: the same number of values.
inline double InterpolateLinear(const Eigen::VectorXd& x, const Eigen::VectorXd& y, double v) {
  const Eigen::Index i = KnotInterval(x, v);
  const double dx = x(i + 1) - x(i);
  const double t = dx > 0 ? std::clamp((v - x(i)) / dx, 0.0, 1.0) : 0.0;
  return y(i) + t * (y(i + 1) - y(i));
}

}  // namespace colonmap::analysis
