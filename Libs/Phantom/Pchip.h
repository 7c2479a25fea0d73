#pragma once
// Shape-preserving piecewise cubic Hermite interpolation (Fritsch-Carlson / MATLAB pchip) of a
// 1-D profile. C1, no overshoot between knots, and monotone data give a monotone function, so it
// serves both for smooth profiles (radius, twist) and for the supine->prone arc-length remap,
// which must stay one-to-one.
#include <cstddef>
#include <vector>

namespace colonmap {
namespace phantom {

class Pchip {
 public:
  Pchip() = default;
  // x: strictly increasing knots (at least 2); y: values at the knots.
  Pchip(std::vector<double> x, std::vector<double> y);

  // Value and first derivative; outside [x.front(), x.back()] the end tangent line is used.
  double operator()(double t) const;
  double Derivative(double t) const;
  // For increasing data only: the t with (*this)(t) == y.
  double Inverse(double y) const;

  bool Empty() const { return x_.empty(); }
  const std::vector<double>& Knots() const { return x_; }
  const std::vector<double>& Values() const { return y_; }

 private:
  std::size_t Interval(double t) const;  // k with x_[k] <= t < x_[k+1], clamped
  std::vector<double> x_, y_, m_;
};

}  // namespace phantom
}  // namespace colonmap
