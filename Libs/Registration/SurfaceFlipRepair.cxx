#include "Registration/SurfaceFlipRepair.h"

#include "Registration/FlatLocator.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <limits>

namespace colonmap::registration {

namespace {

// Cosine between the straight image triangle's normal and the summed target normals at its
// corners (-1 for a degenerate image triangle).
double FacingCosine(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& ref) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double d = n.norm() * ref.norm();
  return d > 0 ? n.dot(ref) / d : -1.0;
}

double SignedArea(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c) {
  const Eigen::Vector2d e = b - a, g = c - a;
  return 0.5 * (e.x() * g.y() - e.y() * g.x());
}

}  // namespace

bool ImageFacesAlongSurface(const Eigen::MatrixXi& F, Eigen::Index f, const Eigen::MatrixXd& position,
                            const Eigen::MatrixXd& normal) {
  const int i = F(f, 0), j = F(f, 1), k = F(f, 2);
  const Eigen::Vector3d ref = normal.row(i) + normal.row(j) + normal.row(k);
  return FacingCosine(position.row(i), position.row(j), position.row(k), ref) > 0.0;
}

int RepairSurfaceFlips(Eigen::MatrixXd& image, const Eigen::MatrixXi& F, const FlatSegment& target,
                       const Eigen::MatrixXd& targetNormals, const Eigen::MatrixXd& position, const Eigen::MatrixXd& normal,
                       const std::vector<Eigen::Index>& badFaces) {
  const Eigen::Index n = image.rows();
  std::vector<std::vector<int>> facesOf(n), neighbours(n);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      facesOf[F(f, k)].push_back(static_cast<int>(f));
      neighbours[F(f, k)].push_back(F(f, (k + 1) % 3));
      neighbours[F(f, k)].push_back(F(f, (k + 2) % 3));
    }
  for (auto& w : neighbours) {
    std::sort(w.begin(), w.end());
    w.erase(std::unique(w.begin(), w.end()), w.end());
  }
  const FlatTriangleLocator locator(target.uv, target.F, target.period);
  Eigen::MatrixXd pos = position, nrm = normal;

  // The worst facing cosine over the faces around v with v's image at p (3D point x, normal m);
  // -inf when a flat image face would be reversed.
  auto worst = [&](int v, const Eigen::Vector2d& p, const Eigen::Vector3d& x, const Eigen::Vector3d& m) {
    double w = std::numeric_limits<double>::infinity();
    for (int f : facesOf[v]) {
      Eigen::Vector2d q[3];
      Eigen::Vector3d y[3], ref(0, 0, 0);
      for (int k = 0; k < 3; ++k) {
        const int c = F(f, k);
        q[k] = c == v ? p : Eigen::Vector2d(image.row(c).transpose());
        y[k] = c == v ? x : Eigen::Vector3d(pos.row(c).transpose());
        ref += c == v ? m : Eigen::Vector3d(nrm.row(c).transpose());
      }
      if (SignedArea(q[0], q[1], q[2]) <= 0.0) return -std::numeric_limits<double>::infinity();
      w = std::min(w, FacingCosine(y[0], y[1], y[2], ref));
    }
    return w;
  };
  auto onTarget = [&](const Eigen::Vector2d& p, Eigen::Vector3d& x, Eigen::Vector3d& m) {
    const FlatHit h = locator.Locate(p);
    x.setZero();
    m.setZero();
    for (int k = 0; k < 3; ++k) {
      x += h.bary(k) * target.position.row(target.F(h.face, k)).transpose();
      m += h.bary(k) * targetNormals.row(target.F(h.face, k)).transpose();
    }
  };

  std::vector<int> corners;
  for (Eigen::Index f : badFaces)
    for (int k = 0; k < 3; ++k) corners.push_back(F(f, k));
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  int moved = 0;
  for (int v : corners) {
    if (neighbours[v].size() != facesOf[v].size()) continue;  // boundary vertex: stays
    const Eigen::Vector2d p0 = image.row(v).transpose();
    double best = worst(v, p0, pos.row(v).transpose(), nrm.row(v).transpose());
    if (best > 0.0) continue;  // already fine (fixed by a neighbour's move)
    Eigen::Vector2d centroid(0, 0);
    for (int w : neighbours[v]) centroid += image.row(w).transpose();
    centroid /= static_cast<double>(neighbours[v].size());
    std::vector<Eigen::Vector2d> goals{centroid};
    for (int w : neighbours[v]) goals.emplace_back(image.row(w).transpose());
    Eigen::Vector2d bestP = p0;
    Eigen::Vector3d bestX, bestM;
    for (std::size_t g = 0; g < goals.size(); ++g)
      for (double t : {0.125, 0.25, 0.5, 0.75, 1.0}) {
        if (g > 0 && t > 0.5) continue;  // towards a neighbour: at most half way (no collapse)
        const Eigen::Vector2d p = p0 + t * (goals[g] - p0);
        Eigen::Vector3d x, m;
        onTarget(p, x, m);
        const double s = worst(v, p, x, m);
        if (s > best) {
          best = s;
          bestP = p;
          bestX = x;
          bestM = m;
        }
      }
    if (bestP == p0) continue;
    image.row(v) = bestP.transpose();
    pos.row(v) = bestX.transpose();
    nrm.row(v) = bestM.transpose();
    ++moved;
  }
  return moved;
}

}  // namespace colonmap::registration
