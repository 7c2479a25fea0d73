#include "Registration/FlatLocator.h"

#include "Core/Error.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace colonmap::registration {

namespace {

// Nearest point to q on segment ab, as the parameter t in [0, 1].
double SegmentParameter(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& q) {
  const Eigen::Vector2d d = b - a;
  const double l2 = d.squaredNorm();
  return l2 > 0 ? std::clamp((q - a).dot(d) / l2, 0.0, 1.0) : 0.0;
}

}  // namespace

FlatTriangleLocator::FlatTriangleLocator(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, double period)
    : uv_(uv), F_(F), period_(period) {
  if (F.rows() == 0 || uv.rows() == 0 || uv.cols() != 2) throw Error("flat locator: empty flat mesh");
  lo_ = uv.colwise().minCoeff().transpose();
  hi_ = uv.colwise().maxCoeff().transpose();
  const Eigen::Vector2d ext = (hi_ - lo_).cwiseMax(1e-12);
  // About two faces per cell.
  cell_ = std::sqrt(ext.x() * ext.y() * 2.0 / static_cast<double>(F.rows()));
  if (!(cell_ > 0)) cell_ = std::max(ext.x(), ext.y());
  nx_ = std::max(1, static_cast<int>(std::ceil(ext.x() / cell_)));
  ny_ = std::max(1, static_cast<int>(std::ceil(ext.y() / cell_)));
  std::vector<long> count(static_cast<std::size_t>(nx_) * ny_ + 1, 0);
  auto forCells = [&](int f, auto&& fn) {
    Eigen::Vector2d a = uv_.row(F_(f, 0)).transpose(), b = a;
    for (int k = 1; k < 3; ++k) {
      a = a.cwiseMin(uv_.row(F_(f, k)).transpose());
      b = b.cwiseMax(uv_.row(F_(f, k)).transpose());
    }
    for (int j = CellY(a.y()); j <= CellY(b.y()); ++j)
      for (int i = CellX(a.x()); i <= CellX(b.x()); ++i) fn(CellIndex(i, j));
  };
  for (int f = 0; f < F_.rows(); ++f) forCells(f, [&](long c) { ++count[c + 1]; });
  for (std::size_t c = 1; c < count.size(); ++c) count[c] += count[c - 1];
  start_ = count;
  faces_.assign(static_cast<std::size_t>(count.back()), -1);
  std::vector<long> fill(start_.begin(), start_.end() - 1);
  for (int f = 0; f < F_.rows(); ++f) forCells(f, [&](long c) { faces_[fill[c]++] = f; });
}

int FlatTriangleLocator::CellX(double u) const {
  return std::clamp(static_cast<int>(std::floor((u - lo_.x()) / cell_)), 0, nx_ - 1);
}
int FlatTriangleLocator::CellY(double v) const {
  return std::clamp(static_cast<int>(std::floor((v - lo_.y()) / cell_)), 0, ny_ - 1);
}

Eigen::Vector3d FlatTriangleLocator::Barycentric(int f, const Eigen::Vector2d& q) const {
  const Eigen::Vector2d a = uv_.row(F_(f, 0)), b = uv_.row(F_(f, 1)), c = uv_.row(F_(f, 2));
  const Eigen::Vector2d e1 = b - a, e2 = c - a, d = q - a;
  const double det = e1.x() * e2.y() - e1.y() * e2.x();
  if (std::fabs(det) < 1e-300) return Eigen::Vector3d(-1, -1, -1);
  const double l1 = (d.x() * e2.y() - d.y() * e2.x()) / det;
  const double l2 = (e1.x() * d.y() - e1.y() * d.x()) / det;
  return Eigen::Vector3d(1.0 - l1 - l2, l1, l2);
}

bool FlatTriangleLocator::Inside(const Eigen::Vector2d& q, FlatHit& best, double& bestMin) const {
  const double tol = 1e-10;
  if (q.x() < lo_.x() - tol || q.x() > hi_.x() + tol || q.y() < lo_.y() - tol || q.y() > hi_.y() + tol) return false;
  const long c = CellIndex(CellX(q.x()), CellY(q.y()));
  bool found = false;
  for (long k = start_[c]; k < start_[c + 1]; ++k) {
    const int f = faces_[k];
    const Eigen::Vector3d b = Barycentric(f, q);
    const double m = b.minCoeff();
    if (m >= -tol && (m > bestMin || (m == bestMin && f < best.face))) {
      bestMin = m;
      best.face = f;
      best.bary = b.cwiseMax(0.0) / b.cwiseMax(0.0).sum();
      found = true;
    }
  }
  return found;
}

void FlatTriangleLocator::Nearest(const Eigen::Vector2d& q, FlatHit& best) const {
  // Rings of cells around q's (clamped) cell until no closer face can remain.
  const int ci = CellX(q.x()), cj = CellY(q.y());
  // Distance from q to the clamped cell's box (q may lie outside the grid).
  const double outside = (q - q.cwiseMax(lo_).cwiseMin(hi_)).norm();
  for (int r = 0; r <= std::max(nx_, ny_); ++r) {
    if (best.face >= 0 && best.distance < outside + (r - 1) * cell_) break;
    for (int j = cj - r; j <= cj + r; ++j) {
      if (j < 0 || j >= ny_) continue;
      for (int i = ci - r; i <= ci + r; ++i) {
        if (i < 0 || i >= nx_ || (std::abs(i - ci) != r && std::abs(j - cj) != r)) continue;
        const long c = CellIndex(i, j);
        for (long k = start_[c]; k < start_[c + 1]; ++k) {
          const int f = faces_[k];
          const std::array<Eigen::Vector2d, 3> p = {uv_.row(F_(f, 0)).transpose(), uv_.row(F_(f, 1)).transpose(),
                                                     uv_.row(F_(f, 2)).transpose()};
          for (int e = 0; e < 3; ++e) {
            const double t = SegmentParameter(p[e], p[(e + 1) % 3], q);
            const double d = (p[e] + t * (p[(e + 1) % 3] - p[e]) - q).norm();
            if (best.face < 0 || d < best.distance || (d == best.distance && f < best.face)) {
              best.face = f;
              best.distance = d;
              best.bary = Eigen::Vector3d::Zero();
              best.bary(e) = 1.0 - t;
              best.bary((e + 1) % 3) = t;
            }
          }
        }
      }
    }
  }
}

FlatHit FlatTriangleLocator::Locate(const Eigen::Vector2d& p) const {
  // Periodic copies of p that fall in the mesh's u range, nearest to the range's middle first.
  std::vector<double> shifts = {0.0};
  if (period_ > 0) {
    const double mid = 0.5 * (lo_.x() + hi_.x());
    const double k0 = std::round((mid - p.x()) / period_);
    shifts = {k0 * period_, (k0 - 1) * period_, (k0 + 1) * period_};
  }
  FlatHit best;
  double bestMin = -std::numeric_limits<double>::infinity();
  for (double s : shifts) {
    FlatHit h;
    double m = -std::numeric_limits<double>::infinity();
    if (Inside(p + Eigen::Vector2d(s, 0.0), h, m) && m > bestMin) {
      best = h;
      bestMin = m;
      best.inside = true;
      best.shift = s;
    }
  }
  if (best.face >= 0) return best;
  for (double s : shifts) {
    FlatHit h;
    Nearest(p + Eigen::Vector2d(s, 0.0), h);
    if (best.face < 0 || h.distance < best.distance) {
      best = h;
      best.shift = s;
    }
  }
  best.inside = false;
  return best;
}

double FlatPeriodFromCut(const Eigen::MatrixXd& uv, const Eigen::MatrixXd& positions) {
  std::map<std::array<double, 3>, std::vector<Eigen::Index>> byPosition;
  for (Eigen::Index i = 0; i < positions.rows(); ++i)
    byPosition[{positions(i, 0), positions(i, 1), positions(i, 2)}].push_back(i);
  std::vector<double> d;
  for (const auto& [p, ids] : byPosition)
    if (ids.size() == 2) d.push_back(std::fabs(uv(ids[0], 0) - uv(ids[1], 0)));
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + d.size() / 2, d.end());
  return d[d.size() / 2];
}

double CheckedFlatPeriod(std::optional<double> reported, const Eigen::MatrixXd& uv, const Eigen::MatrixXd& positions,
                         const std::string& segment, const std::string& what, const std::string& path) {
  const double cut = FlatPeriodFromCut(uv, positions);
  if (!reported) return cut;
  const double w = *reported;
  const double span = uv.rows() > 0 ? uv.col(0).maxCoeff() - uv.col(0).minCoeff() : 0.0;
  const bool fits = cut > 0 ? std::fabs(w - cut) <= 0.01 * cut : span <= 0 || (w <= 2 * span && w >= 0.5 * span);
  const auto number = [](double v) {
    std::ostringstream s;
    s << v;
    return s.str();
  };
  if (!fits)
    throw InputError(what, path, "gives segment " + segment + " a flat width of " + number(w) + ", but its flat map " +
                                     (cut > 0 ? "repeats every " + number(cut) : "spans " + number(span)));
  return w;
}

}  // namespace colonmap::registration
