#pragma once
// The colon wall as seen from a camera: first hit of a ray (the wall point a view axis or an up
// axis points at, DESIGN §2.5) and the nearest wall point of a finding. Brute force over the
// triangles (Moller-Trumbore, closest point on triangle): a view needs a handful of queries on a
// 10^5-face mesh, a few ms each, so no spatial index is worth its build time. Eigen only.
#include <Eigen/Core>

#include <limits>

namespace colonmap::views {

struct WallHit {
  bool hit = false;
  int face = -1;
  Eigen::Vector3d bary{1, 0, 0};  // of `point` in `face`
  Eigen::Vector3d point{0, 0, 0};
  double distance = std::numeric_limits<double>::infinity();  // along the ray, or to the query
};

class CameraWall {
 public:
  // V: n x 3 LPS mm, F: m x 3. Throws colonmap::Error for an empty mesh or out-of-range indices.
  CameraWall(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

  // First triangle hit by origin + t dir, t > minDistance (dir need not be unit; distance is in
  // mm). Ties (a ray through a shared edge) go to the lowest face index: deterministic.
  WallHit Cast(const Eigen::Vector3d& origin, const Eigen::Vector3d& dir, double minDistance = 1e-6) const;
  // Closest point of the mesh to p.
  WallHit Nearest(const Eigen::Vector3d& p) const;
  // Unit normal of a face (orientation of the face's vertex order).
  Eigen::Vector3d FaceNormal(int face) const;

  const Eigen::MatrixXd& V() const { return V_; }
  const Eigen::MatrixXi& F() const { return F_; }

 private:
  Eigen::MatrixXd V_;
  Eigen::MatrixXi F_;
};

// Barycentric combination of per-vertex values (n x 3 rows) at a hit: the image of a wall point
// under a per-vertex map such as registration.vtp's PronePosition.
Eigen::Vector3d InterpolateAtHit(const Eigen::MatrixXd& values, const Eigen::MatrixXi& F, const WallHit& hit);

}  // namespace colonmap::views
