#include "CenterlineCurve.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace colonmap {
namespace phantom {
namespace {

// Resample a polyline at (nearly) equal arc-length spacing; the spacing divides the length.
std::vector<Eigen::Vector3d> ResampleByArcLength(const std::vector<Eigen::Vector3d>& poly, double step) {
  std::vector<double> cum(poly.size(), 0.0);
  for (std::size_t i = 1; i < poly.size(); ++i) cum[i] = cum[i - 1] + (poly[i] - poly[i - 1]).norm();
  const double length = cum.back();
  const std::size_t n = std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(length / step)) + 1);
  std::vector<Eigen::Vector3d> out(n);
  std::size_t seg = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const double u = length * static_cast<double>(i) / static_cast<double>(n - 1);
    while (seg + 2 < poly.size() && cum[seg + 1] < u) ++seg;
    const double len = cum[seg + 1] - cum[seg];
    const double t = len > 0 ? std::clamp((u - cum[seg]) / len, 0.0, 1.0) : 0.0;
    out[i] = (1.0 - t) * poly[seg] + t * poly[seg + 1];
  }
  return out;
}

}  // namespace

CenterlineCurve::CenterlineCurve(const std::vector<Eigen::Vector3d>& waypoints,
                                 const std::vector<double>& filletRadii, double sigmaMm, double stepMm,
                                 const Eigen::Vector3d& normalHint) {
  if (waypoints.size() < 2) throw std::invalid_argument("CenterlineCurve: need two waypoints");
  // 1. Round every inner corner with a circular arc (the fillet radius is the bend radius there,
  // limited so that neighbouring fillets never share more than half a polygon edge).
  const std::size_t nw = waypoints.size();
  // Tangent length each corner wants, then each edge is shared between its two corners in
  // proportion to what they want (a gentle corner leaves more of the edge to a sharp one).
  std::vector<double> phi(nw, 0.0), want(nw, 0.0);
  for (std::size_t i = 1; i + 1 < nw; ++i) {
    const Eigen::Vector3d d1 = (waypoints[i] - waypoints[i - 1]).normalized();
    const Eigen::Vector3d d2 = (waypoints[i + 1] - waypoints[i]).normalized();
    phi[i] = std::acos(std::clamp(d1.dot(d2), -1.0, 1.0));
    const double radius = i < filletRadii.size() ? filletRadii[i] : 0.0;
    want[i] = phi[i] > 1e-6 ? radius * std::tan(0.5 * phi[i]) : 0.0;
  }
  auto share = [&](std::size_t i, std::size_t j) {  // part of edge (i, j) corner i may use
    const double total = want[i] + want[j];
    return total > 0 ? (waypoints[j] - waypoints[i]).norm() * want[i] / total : 0.0;
  };
  std::vector<Eigen::Vector3d> poly{waypoints[0]};
  for (std::size_t i = 1; i + 1 < nw; ++i) {
    const Eigen::Vector3d d1 = (waypoints[i] - waypoints[i - 1]).normalized();
    const Eigen::Vector3d d2 = (waypoints[i + 1] - waypoints[i]).normalized();
    const double t = std::min({want[i], share(i, i - 1), share(i, i + 1)});
    if (phi[i] < 1e-6 || t <= 0.0) {
      poly.push_back(waypoints[i]);
      continue;
    }
    const double R = t / std::tan(0.5 * phi[i]);
    const Eigen::Vector3d n = (d2 - d2.dot(d1) * d1).normalized();
    const Eigen::Vector3d a = waypoints[i] - t * d1, centre = a + R * n;
    const int steps = std::max(2, static_cast<int>(std::ceil(R * phi[i] / 0.25)));
    for (int k = 0; k <= steps; ++k) {
      const double al = phi[i] * k / steps;
      poly.push_back(centre + R * (-std::cos(al) * n + std::sin(al) * d1));
    }
  }
  poly.push_back(waypoints[nw - 1]);
  // 2. Dense resampling, 3. point reflection at both ends (keeps the end points fixed and the
  // ends straight under a symmetric kernel), 4. light Gaussian smoothing (curvature continuous
  // where arcs meet lines), 5. resampling at the final step.
  const double q = 0.5;
  const std::vector<Eigen::Vector3d> dense = ResampleByArcLength(poly, q);
  const double dq = (dense[1] - dense[0]).norm();
  const int ext = static_cast<int>(std::ceil(3.0 * sigmaMm / dq));
  const int n = static_cast<int>(dense.size());
  auto at = [&](int i) -> Eigen::Vector3d {
    if (i < 0) return 2.0 * dense[0] - dense[std::min(-i, n - 1)];
    if (i >= n) return 2.0 * dense[n - 1] - dense[std::max(2 * (n - 1) - i, 0)];
    return dense[i];
  };
  std::vector<double> kernel(2 * ext + 1);
  double ksum = 0.0;
  for (int k = -ext; k <= ext; ++k) {
    const double x = k * dq / sigmaMm;
    kernel[k + ext] = std::exp(-0.5 * x * x);
    ksum += kernel[k + ext];
  }
  std::vector<Eigen::Vector3d> smooth(n);
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d acc = Eigen::Vector3d::Zero();
    for (int k = -ext; k <= ext; ++k) acc += kernel[k + ext] * at(i + k);
    smooth[i] = acc / ksum;
  }
  points_ = ResampleByArcLength(smooth, stepMm);
  const std::size_t m = points_.size();
  step_ = 0.0;
  for (std::size_t i = 1; i < m; ++i) step_ += (points_[i] - points_[i - 1]).norm();
  step_ /= static_cast<double>(m - 1);

  tangents_.resize(m);
  for (std::size_t i = 0; i < m; ++i) {
    if (m == 2) {
      tangents_[i] = (points_[1] - points_[0]) / step_;
    } else if (i == 0) {
      tangents_[i] = (-3.0 * points_[0] + 4.0 * points_[1] - points_[2]) / (2.0 * step_);
    } else if (i + 1 == m) {
      tangents_[i] = (3.0 * points_[m - 1] - 4.0 * points_[m - 2] + points_[m - 3]) / (2.0 * step_);
    } else {
      tangents_[i] = (points_[i + 1] - points_[i - 1]) / (2.0 * step_);
    }
  }
  // Rotation-minimising frame by double reflection (Wang, Juttler, Zheng, Liu 2008).
  normals_.resize(m);
  Eigen::Vector3d t0 = tangents_[0].normalized();
  Eigen::Vector3d n0 = normalHint - normalHint.dot(t0) * t0;
  if (n0.norm() < 1e-6) n0 = t0.unitOrthogonal();
  normals_[0] = n0.normalized();
  for (std::size_t i = 0; i + 1 < m; ++i) {
    const Eigen::Vector3d ti = tangents_[i].normalized(), tn = tangents_[i + 1].normalized();
    const Eigen::Vector3d v1 = points_[i + 1] - points_[i];
    const double c1 = v1.dot(v1);
    const Eigen::Vector3d rL = normals_[i] - (2.0 / c1) * v1.dot(normals_[i]) * v1;
    const Eigen::Vector3d tL = ti - (2.0 / c1) * v1.dot(ti) * v1;
    const Eigen::Vector3d v2 = tn - tL;
    const double c2 = v2.dot(v2);
    Eigen::Vector3d nn = c2 > 1e-20 ? Eigen::Vector3d(rL - (2.0 / c2) * v2.dot(rL) * v2) : rL;
    nn -= nn.dot(tn) * tn;
    normals_[i + 1] = nn.normalized();
  }
}

void CenterlineCurve::Evaluate(double u, Eigen::Vector3d* p, Eigen::Vector3d* d1, Eigen::Vector3d* d2) const {
  const std::size_t m = points_.size();
  const double x = std::clamp(u, 0.0, Length()) / step_;
  const std::size_t i = std::min(static_cast<std::size_t>(x), m - 2);
  const double t = x - static_cast<double>(i), t2 = t * t, t3 = t2 * t;
  const Eigen::Vector3d& P0 = points_[i];
  const Eigen::Vector3d& P1 = points_[i + 1];
  const Eigen::Vector3d M0 = step_ * tangents_[i], M1 = step_ * tangents_[i + 1];
  if (p) *p = (2 * t3 - 3 * t2 + 1) * P0 + (t3 - 2 * t2 + t) * M0 + (-2 * t3 + 3 * t2) * P1 + (t3 - t2) * M1;
  if (d1)
    *d1 = ((6 * t2 - 6 * t) * P0 + (3 * t2 - 4 * t + 1) * M0 + (-6 * t2 + 6 * t) * P1 + (3 * t2 - 2 * t) * M1) / step_;
  if (d2)
    *d2 = ((12 * t - 6) * P0 + (6 * t - 4) * M0 + (-12 * t + 6) * P1 + (6 * t - 2) * M1) / (step_ * step_);
}

Eigen::Vector3d CenterlineCurve::Point(double u) const {
  Eigen::Vector3d p;
  Evaluate(u, &p, nullptr, nullptr);
  return p;
}

void CenterlineCurve::Frame(double u, Eigen::Vector3d& T, Eigen::Vector3d& N, Eigen::Vector3d& B) const {
  Eigen::Vector3d d1;
  Evaluate(u, nullptr, &d1, nullptr);
  T = d1.normalized();
  const std::size_t m = points_.size();
  const double x = std::clamp(u, 0.0, Length()) / step_;
  const std::size_t i = std::min(static_cast<std::size_t>(x), m - 2);
  const double t = x - static_cast<double>(i);
  N = (1.0 - t) * normals_[i] + t * normals_[i + 1];
  N -= N.dot(T) * T;
  N.normalize();
  B = T.cross(N);
}

double CenterlineCurve::Curvature(double u) const {
  Eigen::Vector3d d1, d2;
  Evaluate(u, nullptr, &d1, &d2);
  const double s = d1.norm();
  return d1.cross(d2).norm() / (s * s * s);
}

double CenterlineCurve::Closest(const Eigen::Vector3d& p) const {
  double best = std::numeric_limits<double>::infinity();
  std::size_t bi = 0;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const double d = (points_[i] - p).squaredNorm();
    if (d < best) best = d, bi = i;
  }
  return Refine(p, step_ * static_cast<double>(bi));
}

double CenterlineCurve::Refine(const Eigen::Vector3d& p, double u0) const {
  double u = std::clamp(u0, 0.0, Length());
  Eigen::Vector3d c, d1, d2;
  for (int it = 0; it < 12; ++it) {
    Evaluate(u, &c, &d1, &d2);
    const Eigen::Vector3d r = c - p;
    const double f = r.dot(d1);
    double fp = d1.dot(d1) + r.dot(d2);
    if (fp < 0.25 * d1.dot(d1)) fp = d1.dot(d1);  // far from the curve's centre of curvature only
    const double du = std::clamp(-f / fp, -2.0 * step_, 2.0 * step_);
    const double next = std::clamp(u + du, 0.0, Length());
    if (std::fabs(next - u) < 1e-9) return next;
    u = next;
  }
  return u;
}

}  // namespace phantom
}  // namespace colonmap
