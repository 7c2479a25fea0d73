#include "TubeLocator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap {
namespace phantom {
namespace {
constexpr double kPi = 3.14159265358979323846;

// Squared distance from p to segment [a, b] and the segment parameter of the foot.
double SegmentDistance2(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, double* t) {
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  double x = l2 > 0 ? (p - a).dot(ab) / l2 : 0.0;
  x = std::clamp(x, 0.0, 1.0);
  if (t) *t = x;
  return (a + x * ab - p).squaredNorm();
}
}  // namespace

TubeLocator::TubeLocator(const ScanGeometry& scan, double wallThicknessMm, double bandMm, double cellMm)
    : scan_(&scan), wall_(wallThicknessMm), band_(bandMm), cell_(cellMm) {
  const CenterlineCurve& c = scan.centerline;
  const std::size_t ns = c.NumberOfSamples();
  const double foldExponent = scan.posture == Posture::Prone ? scan.deformation : 0.0;
  // Radius bounds per sample from 32 directions (the base radius is smooth in theta; 2% margin).
  std::vector<double> outer(ns);
  innerBound_.resize(ns);
  for (std::size_t i = 0; i < ns; ++i) {
    const double s = scan.MaterialS(c.Step() * static_cast<double>(i));
    double lo = 1e300, hi = 0.0;
    for (int k = 0; k < 32; ++k) {
      const double r = scan.BaseRadius(s, 2.0 * kPi * k / 32.0);
      lo = std::min(lo, r), hi = std::max(hi, r);
    }
    outer[i] = 1.02 * hi + wall_;
    const double r0 = scan.anatomy.BaseRadius(s);
    innerBound_[i] = 0.98 * (lo / r0) * (r0 - scan.anatomy.MaxDepthNear(s, 3.0, foldExponent)) - 0.5;
  }
  for (std::size_t i = 0; i < ns; i += stride_) nodes_.push_back(c.Sample(i)), nodeU_.push_back(c.Step() * i);
  if ((ns - 1) % stride_ != 0) nodes_.push_back(c.Sample(ns - 1)), nodeU_.push_back(c.Length());
  const std::size_t np = nodes_.size() - 1;
  reach_.resize(np);
  double maxReach = 0.0;
  for (std::size_t j = 0; j < np; ++j) {
    const std::size_t i0 = static_cast<std::size_t>(std::lround(nodeU_[j] / c.Step()));
    const std::size_t i1 = static_cast<std::size_t>(std::lround(nodeU_[j + 1] / c.Step()));
    double r = 0.0;
    for (std::size_t i = i0; i <= i1 && i < ns; ++i) r = std::max(r, outer[i]);
    reach_[j] = r + band_ + 0.5;  // 0.5: chord error of the coarse polyline and slack
    maxReach = std::max(maxReach, reach_[j]);
  }
  // Grid over the tube's bounding box.
  Eigen::Vector3d lo = nodes_[0], hi = nodes_[0];
  for (const auto& n : nodes_) lo = lo.cwiseMin(n), hi = hi.cwiseMax(n);
  gridOrigin_ = lo - Eigen::Vector3d::Constant(maxReach + cell_);
  const Eigen::Vector3d extent = hi - lo + Eigen::Vector3d::Constant(2.0 * (maxReach + cell_));
  for (int d = 0; d < 3; ++d) dims_[d] = static_cast<int>(std::ceil(extent[d] / cell_));
  const std::size_t ncells = static_cast<std::size_t>(dims_[0]) * dims_[1] * dims_[2];
  const double halfDiag = 0.5 * std::sqrt(3.0) * cell_;
  std::vector<std::vector<int>> lists(ncells);
  for (std::size_t j = 0; j < np; ++j) {
    const double reach = reach_[j] + halfDiag;
    const Eigen::Vector3d a = nodes_[j], b = nodes_[j + 1];
    const Eigen::Vector3d bl = a.cwiseMin(b) - Eigen::Vector3d::Constant(reach) - gridOrigin_;
    const Eigen::Vector3d bh = a.cwiseMax(b) + Eigen::Vector3d::Constant(reach) - gridOrigin_;
    int i0[3], i1[3];
    for (int d = 0; d < 3; ++d) {
      i0[d] = std::max(0, static_cast<int>(std::floor(bl[d] / cell_)));
      i1[d] = std::min(dims_[d] - 1, static_cast<int>(std::floor(bh[d] / cell_)));
    }
    for (int z = i0[2]; z <= i1[2]; ++z)
      for (int y = i0[1]; y <= i1[1]; ++y)
        for (int x = i0[0]; x <= i1[0]; ++x) {
          const Eigen::Vector3d centre = gridOrigin_ + cell_ * Eigen::Vector3d(x + 0.5, y + 0.5, z + 0.5);
          if (SegmentDistance2(centre, a, b, nullptr) <= reach * reach)
            lists[(static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x].push_back(static_cast<int>(j));
        }
  }
  cellStart_.assign(ncells + 1, 0);
  for (std::size_t k = 0; k < ncells; ++k) cellStart_[k + 1] = cellStart_[k] + static_cast<int>(lists[k].size());
  pieceIndex_.reserve(cellStart_.back());
  for (const auto& l : lists) pieceIndex_.insert(pieceIndex_.end(), l.begin(), l.end());
}

TubeSample TubeLocator::Query(const Eigen::Vector3d& p) const {
  TubeSample out;
  const Eigen::Vector3d g = (p - gridOrigin_) / cell_;
  const int x = static_cast<int>(std::floor(g.x())), y = static_cast<int>(std::floor(g.y())),
            z = static_cast<int>(std::floor(g.z()));
  if (x < 0 || y < 0 || z < 0 || x >= dims_[0] || y >= dims_[1] || z >= dims_[2]) return out;
  const std::size_t cell = (static_cast<std::size_t>(z) * dims_[1] + y) * dims_[0] + x;
  const int b = cellStart_[cell], e = cellStart_[cell + 1];
  if (b == e) return out;
  // Pick the tube part by distance relative to its reach (a point inside a wide tube can be
  // nearer to a thin neighbour's centreline), then project orthogonally within that part.
  double bestRatio = std::numeric_limits<double>::infinity(), bestT = 0.0;
  int best = -1;
  for (int k = b; k < e; ++k) {
    const int j = pieceIndex_[k];
    double t;
    const double d2 = SegmentDistance2(p, nodes_[j], nodes_[j + 1], &t);
    const double ratio = d2 / (reach_[j] * reach_[j]);
    if (ratio < bestRatio) bestRatio = ratio, best = j, bestT = t;
  }
  if (bestRatio > 1.0) return out;
  const ScanGeometry& scan = *scan_;
  const CenterlineCurve& c = scan.centerline;
  const double u = c.Refine(p, nodeU_[best] + bestT * (nodeU_[best + 1] - nodeU_[best]));
  Eigen::Vector3d T, N, B;
  c.Frame(u, T, N, B);
  Eigen::Vector3d radial = p - c.Point(u);
  const double along = radial.dot(T);
  if (u <= 0.0 && along < 0.0) {
    out.end = -1;
  } else if (u >= c.Length() && along > 0.0) {
    out.end = 1;
  } else {
    radial -= along * T;  // ~0 after Newton; keeps rho exactly radial
  }
  out.near = true;
  out.u = u;
  out.s = scan.MaterialS(u);
  out.rho = radial.norm();
  out.theta = WrapAngle(std::atan2(radial.dot(B), radial.dot(N)) - scan.Twist(out.s));
  const std::size_t si = std::min(static_cast<std::size_t>(std::lround(u / c.Step())), c.NumberOfSamples() - 1);
  const double inner = innerBound_[si];
  if (out.rho < inner - band_ - 1.0) {
    // Far inside the lumen: skip the radius evaluation (distances are upper bounds).
    out.deepLumen = true;
    out.innerRadius = inner;
    out.outerRadius = inner + wall_;
    out.innerDistance = out.rho - inner;
    out.outerDistance = out.rho - inner - wall_;
    return out;
  }
  out.innerRadius = scan.WallRadius(out.s, out.theta);
  out.outerRadius = scan.OuterRadius(out.s, out.theta, wall_);
  double slope = 1.0;
  if (out.end == 0 && std::fabs(out.rho - out.innerRadius) < 4.0 * band_ + 1.0) {
    // Slope of the radial height field: converts the radial gap into a distance to the surface.
    const double ds = 0.3, dt = 0.3 / std::max(out.rho, 1.0);
    const double rs = (scan.WallRadius(out.s + ds, out.theta) - out.innerRadius) / ds / scan.Stretch(out.s);
    const double rt = (scan.WallRadius(out.s, out.theta + dt) - out.innerRadius) / dt / std::max(out.rho, 1.0);
    slope = std::sqrt(1.0 + rs * rs + rt * rt);
  }
  out.innerDistance = (out.rho - out.innerRadius) / slope;
  out.outerDistance = out.rho - out.outerRadius;
  return out;
}

bool TubeLocator::IsLumen(const Eigen::Vector3d& p) const {
  const TubeSample t = Query(p);
  return t.near && t.innerDistance < 0.0 && !(scan_->CollapseDepth(t.u) > 0.0);
}

}  // namespace phantom
}  // namespace colonmap
