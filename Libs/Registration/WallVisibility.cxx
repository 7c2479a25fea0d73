#include "Registration/WallVisibility.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::registration {

WallVisibility::WallVisibility(const TriangleMesh& mesh) : mesh_(mesh) {
  const auto v = mesh.pointData.find("Virtual");
  if (v != mesh.pointData.end() && v->second.values.rows() == mesh.V.rows() && v->second.values.cols() == 1) {
    virtual_ = v->second.values.col(0);
    for (Eigen::Index v = 0; v < virtual_.size(); ++v)
      if (virtual_(v) >= 0.5) virtualVertices_.push_back(v);
    hasVirtual_ = !virtualVertices_.empty();
  }
  const auto a = mesh.pointData.find("CenterlineArcLength");
  if (a != mesh.pointData.end() && a->second.values.rows() == mesh.V.rows() && a->second.values.cols() == 1)
    arc_ = a->second.values.col(0);
}

double WallVisibility::VirtualAt(int face, const Eigen::Vector3d& bary) const {
  if (!hasVirtual_ || face < 0 || face >= mesh_.F.rows()) return 0.0;
  double value = 0.0;
  for (int k = 0; k < 3; ++k) value += bary(k) * virtual_(mesh_.F(face, k));
  return value;
}

OpenPlace WallVisibility::NearestOpen(int face, const Eigen::Vector3d& bary) const {
  OpenPlace best;
  if (face < 0 || face >= mesh_.F.rows()) return best;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  double arc = 0.0;
  for (int k = 0; k < 3; ++k) {
    p += bary(k) * mesh_.V.row(mesh_.F(face, k)).transpose();
    if (arc_.size()) arc += bary(k) * arc_(mesh_.F(face, k));
  }
  const auto isOpen = [&](Eigen::Index v) { return !hasVirtual_ || virtual_(v) < 0.5; };
  // Along the colon first; then, of the open vertices about as far along, the nearest in 3D.
  double leastArc = std::numeric_limits<double>::infinity();
  if (arc_.size())
    for (Eigen::Index v = 0; v < mesh_.V.rows(); ++v)
      if (isOpen(v)) leastArc = std::min(leastArc, std::abs(arc_(v) - arc));
  double least3d = std::numeric_limits<double>::infinity();
  for (Eigen::Index v = 0; v < mesh_.V.rows(); ++v) {
    if (!isOpen(v)) continue;
    if (arc_.size() && std::abs(arc_(v) - arc) > leastArc + 2.0) continue;
    const double d = (mesh_.V.row(v).transpose() - p).norm();
    if (d < least3d) {
      least3d = d;
      best.vertex = static_cast<int>(v);
      best.alongColonMm = arc_.size() ? std::abs(arc_(v) - arc) : d;
    }
  }
  return best;
}

double WallVisibility::DistanceToVirtual(const Eigen::Vector3d& point) const {
  double least = std::numeric_limits<double>::infinity();
  for (const Eigen::Index v : virtualVertices_) least = std::min(least, (mesh_.V.row(v).transpose() - point).squaredNorm());
  return std::sqrt(least);
}

bool WallVisibility::OffSeenWall(const Eigen::Vector3d& point, double wallDistanceMm) const {
  return hasVirtual_ && wallDistanceMm > offWallMm && DistanceToVirtual(point) < wallDistanceMm + nearVirtualMm;
}

}  // namespace colonmap::registration
