#include "Views/CameraWall.h"

#include "Core/Error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace colonmap::views {

namespace {

// Closest point on triangle (a, b, c) to p (Ericson, Real-Time Collision Detection 5.1.5);
// returns barycentric coordinates.
Eigen::Vector3d ClosestBary(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double denom = 1.0 / (va + vb + vc);
  const double v = vb * denom, w = vc * denom;
  return {1 - v - w, v, w};
}

}  // namespace

CameraWall::CameraWall(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) : V_(V), F_(F) {
  if (V_.rows() == 0 || F_.rows() == 0 || V_.cols() != 3 || F_.cols() != 3)
    throw Error("wall mesh: no triangles");
  if (F_.minCoeff() < 0 || F_.maxCoeff() >= V_.rows()) throw Error("wall mesh: face index out of range");
}

WallHit CameraWall::Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double minDistance) const {
  WallHit best;
  const double len = dir.norm();
  if (!(len > 0)) return best;
  const Eigen::Vector3d d = dir / len;
  for (Eigen::Index f = 0; f < F_.rows(); ++f) {
    const Eigen::Vector3d a = V_.row(F_(f, 0)), b = V_.row(F_(f, 1)), c = V_.row(F_(f, 2));
    const Eigen::Vector3d e1 = b - a, e2 = c - a;
    const Eigen::Vector3d pv = d.cross(e2);
    const double det = e1.dot(pv);
    if (std::abs(det) < 1e-14) continue;
    const double inv = 1.0 / det;
    const Eigen::Vector3d tv = origin - a;
    const double u = tv.dot(pv) * inv;
    if (u < 0 || u > 1) continue;
    const Eigen::Vector3d qv = tv.cross(e1);
    const double v = d.dot(qv) * inv;
    if (v < 0 || u + v > 1) continue;
    const double t = e2.dot(qv) * inv;
    if (t <= minDistance || t >= best.distance) continue;
    best.hit = true;
    best.face = static_cast<int>(f);
    best.bary = Eigen::Vector3d(1 - u - v, u, v);
    best.distance = t;
  }
  if (best.hit) best.point = origin + best.distance * d;
  return best;
}

WallHit CameraWall::Nearest(const Eigen::Vector3d& p) const {
  WallHit best;
  for (Eigen::Index f = 0; f < F_.rows(); ++f) {
    const Eigen::Vector3d a = V_.row(F_(f, 0)), b = V_.row(F_(f, 1)), c = V_.row(F_(f, 2));
    // Cheap reject: the triangle's bounding sphere is farther than the best so far.
    const Eigen::Vector3d m = (a + b + c) / 3.0;
    const double r = std::sqrt(std::max({(a - m).squaredNorm(), (b - m).squaredNorm(), (c - m).squaredNorm()}));
    if ((p - m).norm() - r >= best.distance) continue;
    const Eigen::Vector3d w = ClosestBary(p, a, b, c);
    const Eigen::Vector3d q = w(0) * a + w(1) * b + w(2) * c;
    const double dist = (p - q).norm();
    if (dist < best.distance) {
      best.hit = true;
      best.face = static_cast<int>(f);
      best.bary = w;
      best.point = q;
      best.distance = dist;
    }
  }
  return best;
}

Eigen::Vector3d CameraWall::FaceNormal(int face) const {
  const Eigen::Vector3d a = V_.row(F_(face, 0)), b = V_.row(F_(face, 1)), c = V_.row(F_(face, 2));
  return (b - a).cross(c - a).normalized();
}

Eigen::Vector3d InterpolateAtHit(const Eigen::MatrixXd& values, const Eigen::MatrixXi& F, const WallHit& hit) {
  if (!hit.hit || hit.face < 0) throw Error("wall map: no wall point to map");
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) out += hit.bary(k) * values.row(F(hit.face, k)).transpose();
  return out;
}

}  // namespace colonmap::views
