#include "Views/SkeletonCorrespondence.h"

#include "Core/Error.h"

#include <Eigen/Geometry>
#include <Eigen/SVD>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace colonmap::views {

namespace {

const Eigen::MatrixXd& PointArray(const TriangleMesh& mesh, const std::string& name, int components,
                                  const std::string& what) {
  const auto it = mesh.pointData.find(name);
  if (it == mesh.pointData.end()) throw Error(what + ": no point array " + name);
  if (it->second.values.rows() != mesh.V.rows() || it->second.values.cols() != components)
    throw Error(what + ": point array " + name + " has the wrong size");
  return it->second.values;
}

// The proper rotation R minimising sum w |R (x - cx) - (y - cy)|^2, from H = sum w (x-cx)(y-cy)^T.
Eigen::Matrix3d Kabsch(const Eigen::Matrix3d& H) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixV() * D * svd.matrixU().transpose();
}

struct RowSum {
  double w = 0, wv = 0;
  Eigen::Vector3d wx = Eigen::Vector3d::Zero(), wy = Eigen::Vector3d::Zero();
  Eigen::Matrix3d wxy = Eigen::Matrix3d::Zero();
  std::vector<bool> sectors;
};

}  // namespace

LinkedSkeleton::LinkedSkeleton(const TriangleMesh& mesh, const std::string& what, const SkeletonOptions& options) {
  const Eigen::MatrixXd& uv = PointArray(mesh, "SupineFlatUV", 2, what);
  const Eigen::MatrixXd& image = PointArray(mesh, "PronePosition", 3, what);
  const auto segIt = mesh.pointData.find("SegmentId");
  const bool hasSegments = segIt != mesh.pointData.end() && segIt->second.values.rows() == mesh.V.rows();
  const Eigen::Index n = mesh.V.rows();
  if (n == 0 || mesh.F.rows() == 0) throw Error(what + ": empty mesh");

  // Vertex areas (a third of each incident face): mass centres weighted by area, so that uneven
  // meshing around a loop does not pull its centre.
  Eigen::VectorXd area = Eigen::VectorXd::Zero(n);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    const double A = 0.5 * (b - a).cross(c - a).norm() / 3.0;
    for (int k = 0; k < 3; ++k) area(mesh.F(f, k)) += A;
  }

  std::map<int, std::vector<Eigen::Index>> bySegment;
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(area(i) > 0)) continue;  // unreferenced vertex
    bySegment[hasSegments ? static_cast<int>(std::lround(segIt->second.values(i, 0))) : 0].push_back(i);
  }
  // Anal end first: R, S, D, T, A = SegmentId 4, 3, 2, 1, 0.
  for (auto s = bySegment.rbegin(); s != bySegment.rend(); ++s) {
    const std::vector<Eigen::Index>& ids = s->second;
    double u0 = uv(ids[0], 0), u1 = u0, v0 = uv(ids[0], 1), v1 = v0;
    for (Eigen::Index i : ids) {
      u0 = std::min(u0, uv(i, 0));
      u1 = std::max(u1, uv(i, 0));
      v0 = std::min(v0, uv(i, 1));
      v1 = std::max(v1, uv(i, 1));
    }
    const double width = u1 - u0;
    if (!(width > 0)) continue;
    const double dv = width / options.rowsPerWidth;
    const int nRows = std::max(1, static_cast<int>(std::ceil((v1 - v0) / dv)));
    std::vector<RowSum> sums(nRows);
    for (RowSum& r : sums) r.sectors.assign(options.sectors, false);
    for (Eigen::Index i : ids) {
      const int k = std::clamp(static_cast<int>(std::floor((uv(i, 1) - v0) / dv)), 0, nRows - 1);
      const int sector = std::clamp(static_cast<int>(std::floor((uv(i, 0) - u0) / width * options.sectors)), 0,
                                    options.sectors - 1);
      RowSum& r = sums[k];
      const double w = area(i);
      const Eigen::Vector3d x = mesh.V.row(i), y = image.row(i);
      r.w += w;
      r.wv += w * uv(i, 1);
      r.wx += w * x;
      r.wy += w * y;
      r.wxy += w * x * y.transpose();
      r.sectors[sector] = true;
    }
    for (const RowSum& r : sums) {
      if (!(r.w > 0) || std::count(r.sectors.begin(), r.sectors.end(), true) < options.minSectors) continue;
      SkeletonRow row;
      row.segment = s->first;
      row.weight = r.w;
      row.v = r.wv / r.w;
      row.supine = r.wx / r.w;
      row.prone = r.wy / r.w;
      row.rotation = Kabsch(r.wxy - r.w * row.supine * row.prone.transpose());
      rows_.push_back(row);
    }
  }
  if (rows_.size() < 2) throw Error(what + ": fewer than two loops around the flattened segments (no skeleton)");
  arc_.assign(rows_.size(), 0.0);
  for (std::size_t k = 1; k < rows_.size(); ++k) arc_[k] = arc_[k - 1] + (rows_[k].supine - rows_[k - 1].supine).norm();
}

SkeletonLocation LinkedSkeleton::Locate(int row, double t) const {
  SkeletonLocation l;
  l.row = row;
  l.t = t;
  l.arc = arc_[row] + t * (arc_[row + 1] - arc_[row]);
  l.supine = (1 - t) * rows_[row].supine + t * rows_[row + 1].supine;
  return l;
}

SkeletonLocation LinkedSkeleton::Project(const Eigen::Vector3d& p) const {
  SkeletonLocation best;
  best.distance = std::numeric_limits<double>::infinity();
  for (std::size_t k = 0; k + 1 < rows_.size(); ++k) {
    const Eigen::Vector3d a = rows_[k].supine, d = rows_[k + 1].supine - a;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - a).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (a + t * d - p).norm();
    if (dist < best.distance) {
      best = Locate(static_cast<int>(k), t);
      best.distance = dist;
    }
  }
  return best;
}

SkeletonLocation LinkedSkeleton::AtArc(double arc) const {
  arc = std::clamp(arc, 0.0, arc_.back());
  std::size_t k = std::upper_bound(arc_.begin(), arc_.end(), arc) - arc_.begin();
  k = std::clamp<std::size_t>(k, 1, arc_.size() - 1) - 1;
  const double len = arc_[k + 1] - arc_[k];
  return Locate(static_cast<int>(k), len > 0 ? std::clamp((arc - arc_[k]) / len, 0.0, 1.0) : 0.0);
}

Eigen::Vector3d LinkedSkeleton::Supine(const SkeletonLocation& l) const {
  return (1 - l.t) * rows_[l.row].supine + l.t * rows_[l.row + 1].supine;
}

Eigen::Vector3d LinkedSkeleton::Prone(const SkeletonLocation& l) const {
  return (1 - l.t) * rows_[l.row].prone + l.t * rows_[l.row + 1].prone;
}

Eigen::Matrix3d LinkedSkeleton::Rotation(const SkeletonLocation& l) const {
  const Eigen::Quaterniond a(rows_[l.row].rotation), b(rows_[l.row + 1].rotation);
  return a.slerp(l.t, b).toRotationMatrix();
}

Eigen::Vector3d LinkedSkeleton::MapPoint(const Eigen::Vector3d& o) const {
  const SkeletonLocation l = Project(o);
  return Prone(l) + Rotation(l) * (o - Supine(l));
}

}  // namespace colonmap::views
