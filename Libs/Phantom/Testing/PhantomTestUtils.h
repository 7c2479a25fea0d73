#pragma once
// Small helpers shared by the phantom tests.
#include <Phantom/Phantom.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

namespace colonmap {
namespace phantom {
namespace testing {

constexpr double kPi = 3.14159265358979323846;

inline PhantomOptions CoarseOptions(std::uint32_t seed = 1, double deformation = 0.5) {
  PhantomOptions o;
  o.seed = seed;
  o.deformation = deformation;
  o.spacing = Eigen::Vector3d(2.5, 2.5, 2.5);
  return o;
}

// Largest outer radius of the tube over theta at material s.
inline double MaxOuterRadius(const ScanGeometry& scan, double s, double wall) {
  double r = 0.0;
  for (int k = 0; k < 64; ++k) r = std::max(r, scan.OuterRadius(s, 2.0 * kPi * k / 64.0, wall));
  return r;
}

// Trilinear interpolation of a volume at a physical point (identity direction).
inline double Trilinear(const Volume<short>& v, const Eigen::Vector3d& p) {
  const Eigen::Vector3d c = v.PhysicalToIndex(p);
  const long i = static_cast<long>(std::floor(c.x())), j = static_cast<long>(std::floor(c.y())),
             k = static_cast<long>(std::floor(c.z()));
  const double fx = c.x() - i, fy = c.y() - j, fz = c.z() - k;
  double acc = 0.0;
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const long ii = std::clamp(i + dx, 0L, long(v.size[0]) - 1), jj = std::clamp(j + dy, 0L, long(v.size[1]) - 1),
                   kk = std::clamp(k + dz, 0L, long(v.size[2]) - 1);
        acc += (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) * (dz ? fz : 1 - fz) * v.At(ii, jj, kk);
      }
  return acc;
}

// Distance from p to triangle (a, b, c) (Ericson, Real-Time Collision Detection 5.1.5).
inline double PointTriangleDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1.0 / (va + vb + vc);
  return (p - (a + ab * (vb * denom) + ac * (vc * denom))).norm();
}

// Distance from p (at material s) to a TrueWall mesh, searching the grid rows around s.
inline double DistanceToWall(const TriangleMesh& mesh, int pointsAround, double length, const Eigen::Vector3d& p,
                             double s) {
  const int rows = static_cast<int>(mesh.V.rows() / pointsAround);
  const int row = static_cast<int>(s / length * (rows - 1));
  double best = 1e300;
  for (int i = std::max(0, row - 3); i <= std::min(rows - 2, row + 3); ++i)
    for (Eigen::Index f = 2L * i * pointsAround; f < 2L * (i + 1) * pointsAround; ++f)
      best = std::min(best, PointTriangleDistance(p, mesh.V.row(mesh.F(f, 0)).transpose(),
                                                  mesh.V.row(mesh.F(f, 1)).transpose(),
                                                  mesh.V.row(mesh.F(f, 2)).transpose()));
  return best;
}

}  // namespace testing
}  // namespace phantom
}  // namespace colonmap
