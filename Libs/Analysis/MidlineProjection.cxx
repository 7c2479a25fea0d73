#include "MidlineProjection.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace colonmap {
namespace analysis {

namespace {
constexpr double kTwoPi = 6.283185307179586476925;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

Eigen::Vector3d PerpendicularNear(const Eigen::Vector3d& t, const Eigen::Vector3d& hint) {
  Eigen::Vector3d n = hint - hint.dot(t) * t;
  if (n.norm() < 1e-6 * std::max(1.0, hint.norm())) {
    Eigen::Index axis = 0;
    t.cwiseAbs().minCoeff(&axis);
    n = Eigen::Vector3d::Unit(axis) - t(axis) * t;
  }
  return n.normalized();
}
}  // namespace

Eigen::VectorXd ArcLength(const Eigen::MatrixXd& polyline) {
  Eigen::VectorXd c(polyline.rows());
  if (polyline.rows() == 0) return c;
  c(0) = 0.0;
  for (Eigen::Index i = 1; i < polyline.rows(); ++i) c(i) = c(i - 1) + (polyline.row(i) - polyline.row(i - 1)).norm();
  return c;
}

Eigen::Vector3d PointAtArc(const Eigen::MatrixXd& P, const Eigen::VectorXd& arc, double s) {
  const Eigen::Index n = P.rows();
  const Eigen::Index i = std::clamp<Eigen::Index>(std::upper_bound(arc.data(), arc.data() + n, s) - arc.data() - 1, 0, n - 2);
  const double len = arc(i + 1) - arc(i), t = len > 0 ? std::clamp((s - arc(i)) / len, 0.0, 1.0) : 0.0;
  return ((1 - t) * P.row(i) + t * P.row(i + 1)).transpose();
}

void SegmentFrames(const Eigen::MatrixXd& polyline, Eigen::MatrixXd& T, Eigen::MatrixXd& N, Eigen::MatrixXd& B,
                   const Eigen::Vector3d& normalHint) {
  const Eigen::Index m = std::max<Eigen::Index>(0, polyline.rows() - 1);
  T.resize(m, 3), N.resize(m, 3), B.resize(m, 3);
  Eigen::Vector3d t(1, 0, 0), n(0, 1, 0);
  bool started = false;
  for (Eigen::Index i = 0; i < m; ++i) {
    Eigen::Vector3d d = (polyline.row(i + 1) - polyline.row(i)).transpose();
    const double len = d.norm();
    if (len > 0.0) {
      d /= len;
      if (!started) {
        t = d, n = PerpendicularNear(t, normalHint), started = true;
      } else {
        // Minimal rotation taking t onto d (parallel transport of the discrete curve).
        const Eigen::Vector3d v = t.cross(d);
        const double c = t.dot(d);
        if (c > -1.0 + 1e-12) {
          n = n + v.cross(n) + v.cross(v.cross(n)) / (1.0 + c);
        }
        t = d;
        n = PerpendicularNear(t, n);
      }
    }
    T.row(i) = t.transpose(), N.row(i) = n.transpose(), B.row(i) = t.cross(n).transpose();
  }
  // Leading zero-length segments take the first real frame.
  Eigen::Index first = 0;
  while (first < m && (polyline.row(first + 1) - polyline.row(first)).norm() == 0.0) ++first;
  for (Eigen::Index i = 0; i < first && first < m; ++i) T.row(i) = T.row(first), N.row(i) = N.row(first), B.row(i) = B.row(first);
}

MidlineProjection ProjectToMidline(const Eigen::MatrixXd& points, const Eigen::MatrixXd& midline,
                                   const ProjectionOptions& options) {
  if (points.cols() != 3 || midline.cols() != 3) throw std::invalid_argument("ProjectToMidline: points and midline need 3 columns");
  const Eigen::Index n = points.rows();
  MidlineProjection out;
  out.arc = Eigen::VectorXd::Constant(n, kNaN);
  out.distance = Eigen::VectorXd::Constant(n, kNaN);
  out.angle = Eigen::VectorXd::Constant(n, kNaN);
  out.segment = Eigen::VectorXi::Constant(n, -1);
  const Eigen::Index ns = midline.rows() - 1;
  if (ns < 1 || n == 0) return out;

  const Eigen::VectorXd cum = ArcLength(midline);
  Eigen::MatrixXd T, N, B;
  SegmentFrames(midline, T, N, B, options.normalHint);

  // Grid over the midline's bounding box.
  const Eigen::Vector3d lo = midline.colwise().minCoeff().transpose();
  const Eigen::Vector3d hi = midline.colwise().maxCoeff().transpose();
  double h = options.cellSize;
  if (!(h > 0.0)) {
    std::vector<double> lens(static_cast<std::size_t>(ns));
    for (Eigen::Index i = 0; i < ns; ++i) lens[static_cast<std::size_t>(i)] = cum(i + 1) - cum(i);
    std::nth_element(lens.begin(), lens.begin() + ns / 2, lens.end());
    h = std::max(8.0 * lens[static_cast<std::size_t>(ns / 2)], (hi - lo).norm() / 64.0);
    if (!(h > 0.0)) h = 1.0;
  }
  Eigen::Array3i dims;
  for (;;) {
    for (int a = 0; a < 3; ++a) dims(a) = static_cast<int>(std::floor((hi(a) - lo(a)) / h)) + 1;
    if (static_cast<double>(dims(0)) * dims(1) * dims(2) <= 4e6) break;
    h *= 1.5;  // keep the grid small
  }
  const auto cellOf = [&](const Eigen::Vector3d& p, int a) { return static_cast<int>(std::floor((p(a) - lo(a)) / h)); };
  const auto flat = [&](int x, int y, int z) {
    return (static_cast<std::size_t>(z) * dims(1) + static_cast<std::size_t>(y)) * dims(0) + static_cast<std::size_t>(x);
  };
  const std::size_t nCells = static_cast<std::size_t>(dims(0)) * dims(1) * dims(2);
  std::vector<int> start(nCells + 1, 0), items;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<int> fill;
    if (pass == 1) {
      for (std::size_t c = 0; c < nCells; ++c) start[c + 1] += start[c];
      items.resize(static_cast<std::size_t>(start[nCells]));
      fill.assign(start.begin(), start.end() - 1);
    }
    for (Eigen::Index s = 0; s < ns; ++s) {
      const Eigen::Vector3d a = midline.row(s).transpose(), b = midline.row(s + 1).transpose();
      const Eigen::Vector3d smin = a.cwiseMin(b), smax = a.cwiseMax(b);
      int c0[3], c1[3];
      for (int k = 0; k < 3; ++k) c0[k] = std::clamp(cellOf(smin, k), 0, dims(k) - 1), c1[k] = std::clamp(cellOf(smax, k), 0, dims(k) - 1);
      for (int z = c0[2]; z <= c1[2]; ++z)
        for (int y = c0[1]; y <= c1[1]; ++y)
          for (int x = c0[0]; x <= c1[0]; ++x) {
            const std::size_t c = flat(x, y, z);
            if (pass == 0) ++start[c + 1];
            else items[static_cast<std::size_t>(fill[c]++)] = static_cast<int>(s);
          }
    }
  }

  std::vector<Eigen::Index> stamp(static_cast<std::size_t>(ns), -1);
  const int maxRing = dims.maxCoeff() + 1;
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::Vector3d p = points.row(i).transpose();
    int q[3];
    for (int a = 0; a < 3; ++a) q[a] = cellOf(p, a);
    double best2 = std::numeric_limits<double>::infinity(), bestT = 0.0, bestTRaw = 0.0;
    Eigen::Index bestS = -1;
    const auto visit = [&](int x, int y, int z) {
      const std::size_t c = flat(x, y, z);
      for (int k = start[c]; k < start[c + 1]; ++k) {
        const int s = items[static_cast<std::size_t>(k)];
        if (stamp[static_cast<std::size_t>(s)] == i) continue;
        stamp[static_cast<std::size_t>(s)] = i;
        const Eigen::Vector3d a = midline.row(s).transpose(), e = midline.row(s + 1).transpose() - a;
        const double ee = e.squaredNorm();
        const double traw = ee > 0.0 ? (p - a).dot(e) / ee : 0.0;
        const double t = std::clamp(traw, 0.0, 1.0);
        const double d2 = (a + t * e - p).squaredNorm();
        if (d2 < best2) best2 = d2, bestT = t, bestTRaw = traw, bestS = s;
      }
    };
    for (int k = 0; k <= maxRing; ++k) {
      // Ring k: cells at Chebyshev distance exactly k from q, clipped to the grid.
      const int z0 = std::max(q[2] - k, 0), z1 = std::min(q[2] + k, dims(2) - 1);
      const int y0 = std::max(q[1] - k, 0), y1 = std::min(q[1] + k, dims(1) - 1);
      const int x0 = std::max(q[0] - k, 0), x1 = std::min(q[0] + k, dims(0) - 1);
      for (int z = z0; z <= z1; ++z)
        for (int y = y0; y <= y1; ++y) {
          if (std::abs(z - q[2]) == k || std::abs(y - q[1]) == k) {
            for (int x = x0; x <= x1; ++x) visit(x, y, z);
          } else {
            if (q[0] - k >= 0 && q[0] - k < dims(0)) visit(q[0] - k, y, z);
            if (k > 0 && q[0] + k >= 0 && q[0] + k < dims(0)) visit(q[0] + k, y, z);
          }
        }
      // Every unvisited segment lies in cells of ring >= k + 1: at least k * h away.
      const double bound = k * h;
      if (bestS >= 0 && best2 <= bound * bound) break;
      if (bound > options.maxDistance) break;
      if (q[0] - k <= 0 && q[1] - k <= 0 && q[2] - k <= 0 && q[0] + k >= dims(0) - 1 && q[1] + k >= dims(1) - 1 &&
          q[2] + k >= dims(2) - 1)
        break;  // the whole grid has been visited
    }
    if (bestS < 0) continue;
    const double dist = std::sqrt(best2);
    out.distance(i) = dist;
    out.segment(i) = static_cast<int>(bestS);
    const Eigen::Vector3d a = midline.row(bestS).transpose(), e = midline.row(bestS + 1).transpose() - a;
    const Eigen::Vector3d d = p - (a + bestT * e);
    double ang = std::atan2(d.dot(B.row(bestS).transpose()), d.dot(N.row(bestS).transpose()));
    if (ang < 0.0) ang += kTwoPi;
    out.angle(i) = ang >= kTwoPi ? 0.0 : ang;
    const bool beyond = (bestS == 0 && bestTRaw < 0.0) || (bestS == ns - 1 && bestTRaw > 1.0);
    if ((options.excludeBeyondEnds && beyond) || dist > options.maxDistance) continue;
    out.arc(i) = cum(bestS) + bestT * (cum(bestS + 1) - cum(bestS));
  }
  return out;
}

}  // namespace analysis
}  // namespace colonmap
