#include "Pchip.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace colonmap {
namespace phantom {
namespace {
double Sign(double v) { return v > 0 ? 1.0 : (v < 0 ? -1.0 : 0.0); }

// One-sided three-point end slope, limited so that it keeps the shape (as in MATLAB pchip).
double EndSlope(double h0, double h1, double d0, double d1) {
  double m = ((2.0 * h0 + h1) * d0 - h0 * d1) / (h0 + h1);
  if (Sign(m) != Sign(d0)) {
    m = 0.0;
  } else if (Sign(d0) != Sign(d1) && std::fabs(m) > 3.0 * std::fabs(d0)) {
    m = 3.0 * d0;
  }
  return m;
}
}  // namespace

Pchip::Pchip(std::vector<double> x, std::vector<double> y) : x_(std::move(x)), y_(std::move(y)) {
  const std::size_t n = x_.size();
  if (n < 2 || y_.size() != n) throw std::invalid_argument("Pchip: need >= 2 knots and one value per knot");
  for (std::size_t k = 0; k + 1 < n; ++k)
    if (!(x_[k + 1] > x_[k])) throw std::invalid_argument("Pchip: knots must increase strictly");
  std::vector<double> h(n - 1), d(n - 1);
  for (std::size_t k = 0; k + 1 < n; ++k) {
    h[k] = x_[k + 1] - x_[k];
    d[k] = (y_[k + 1] - y_[k]) / h[k];
  }
  m_.assign(n, 0.0);
  if (n == 2) {
    m_[0] = m_[1] = d[0];
    return;
  }
  for (std::size_t k = 1; k + 1 < n; ++k) {
    if (d[k - 1] * d[k] <= 0.0) continue;  // local extremum: flat tangent, no overshoot
    const double w1 = 2.0 * h[k] + h[k - 1], w2 = h[k] + 2.0 * h[k - 1];
    m_[k] = (w1 + w2) / (w1 / d[k - 1] + w2 / d[k]);
  }
  m_[0] = EndSlope(h[0], h[1], d[0], d[1]);
  m_[n - 1] = EndSlope(h[n - 2], h[n - 3], d[n - 2], d[n - 3]);
}

std::size_t Pchip::Interval(double t) const {
  const auto it = std::upper_bound(x_.begin(), x_.end(), t);
  std::size_t k = it == x_.begin() ? 0 : static_cast<std::size_t>(it - x_.begin()) - 1;
  return std::min(k, x_.size() - 2);
}

double Pchip::operator()(double t) const {
  if (t <= x_.front()) return y_.front() + m_.front() * (t - x_.front());
  if (t >= x_.back()) return y_.back() + m_.back() * (t - x_.back());
  const std::size_t k = Interval(t);
  const double h = x_[k + 1] - x_[k], s = (t - x_[k]) / h;
  const double s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * y_[k] + (s3 - 2 * s2 + s) * h * m_[k] + (-2 * s3 + 3 * s2) * y_[k + 1] +
         (s3 - s2) * h * m_[k + 1];
}

double Pchip::Derivative(double t) const {
  if (t <= x_.front()) return m_.front();
  if (t >= x_.back()) return m_.back();
  const std::size_t k = Interval(t);
  const double h = x_[k + 1] - x_[k], s = (t - x_[k]) / h;
  const double s2 = s * s;
  return ((6 * s2 - 6 * s) * y_[k] + (-6 * s2 + 6 * s) * y_[k + 1]) / h + (3 * s2 - 4 * s + 1) * m_[k] +
         (3 * s2 - 2 * s) * m_[k + 1];
}

double Pchip::Inverse(double y) const {
  if (y <= y_.front()) return m_.front() > 0 ? x_.front() + (y - y_.front()) / m_.front() : x_.front();
  if (y >= y_.back()) return m_.back() > 0 ? x_.back() + (y - y_.back()) / m_.back() : x_.back();
  const auto it = std::upper_bound(y_.begin(), y_.end(), y);
  const std::size_t k = std::min(static_cast<std::size_t>(it - y_.begin()) - 1, x_.size() - 2);
  // Safeguarded Newton inside the bracketing interval (the cubic is monotone there).
  double lo = x_[k], hi = x_[k + 1];
  double t = lo + (hi - lo) * (y - y_[k]) / (y_[k + 1] - y_[k]);
  for (int it2 = 0; it2 < 60; ++it2) {
    const double f = (*this)(t) - y;
    if (f > 0) hi = t; else lo = t;
    const double df = Derivative(t);
    double next = df > 0 ? t - f / df : 0.5 * (lo + hi);
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::fabs(next - t) < 1e-12 * (1.0 + std::fabs(t))) return next;
    t = next;
  }
  return t;
}

}  // namespace phantom
}  // namespace colonmap
