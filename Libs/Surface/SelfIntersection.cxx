#include "Surface/SelfIntersection.h"


#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>

namespace colonmap::surface {
namespace {

double Orient(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  return (b - a).cross(c - a).dot(d - a);
}

bool TrianglesCross(const Eigen::Vector3d t[3], const Eigen::Vector3d u[3]) {
  for (int i = 0; i < 3; ++i) {
    if (SegmentCrossesTriangle(t[i], t[(i + 1) % 3], u[0], u[1], u[2])) return true;
    if (SegmentCrossesTriangle(u[i], u[(i + 1) % 3], t[0], t[1], t[2])) return true;
  }
  return false;
}

}  // namespace

bool SegmentCrossesTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const double dp = Orient(a, b, c, p), dq = Orient(a, b, c, q);
  if (!((dp > 0 && dq < 0) || (dp < 0 && dq > 0))) return false;
  const double e1 = Orient(p, q, a, b), e2 = Orient(p, q, b, c), e3 = Orient(p, q, c, a);
  return (e1 > 0 && e2 > 0 && e3 > 0) || (e1 < 0 && e2 < 0 && e3 < 0);
}

SelfIntersections FindSelfIntersections(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, std::size_t maxExamples) {
  SelfIntersections out;
  const Eigen::Index m = F.rows();
  if (m < 2) return out;
  // Cell size: twice the mean edge length.
  double edge = 0.0;
  for (Eigen::Index f = 0; f < m; ++f) edge += (V.row(F(f, 0)) - V.row(F(f, 1))).norm();
  const double cell = std::max(1e-9, 2.0 * edge / static_cast<double>(m));
  const Eigen::RowVector3d origin = V.colwise().minCoeff();
  std::vector<Eigen::RowVector3d> lo(static_cast<std::size_t>(m)), hi(static_cast<std::size_t>(m));
  std::vector<std::pair<std::uint64_t, int>> entries;
  const auto index = [&](double x, int axis) { return static_cast<std::uint64_t>(std::floor((x - origin(axis)) / cell)); };
  const auto key = [](std::uint64_t x, std::uint64_t y, std::uint64_t z) { return (x << 42) | (y << 21) | z; };
  for (Eigen::Index f = 0; f < m; ++f) {
    lo[f] = V.row(F(f, 0)).cwiseMin(V.row(F(f, 1))).cwiseMin(V.row(F(f, 2)));
    hi[f] = V.row(F(f, 0)).cwiseMax(V.row(F(f, 1))).cwiseMax(V.row(F(f, 2)));
    for (std::uint64_t z = index(lo[f](2), 2); z <= index(hi[f](2), 2); ++z)
      for (std::uint64_t y = index(lo[f](1), 1); y <= index(hi[f](1), 1); ++y)
        for (std::uint64_t x = index(lo[f](0), 0); x <= index(hi[f](0), 0); ++x)
          entries.emplace_back(key(x, y, z), static_cast<int>(f));
  }
  std::sort(entries.begin(), entries.end());
  for (std::size_t a = 0; a < entries.size();) {
    std::size_t b = a;
    while (b < entries.size() && entries[b].first == entries[a].first) ++b;
    const std::uint64_t here = entries[a].first;
    for (std::size_t i = a; i < b; ++i)
      for (std::size_t j = i + 1; j < b; ++j) {
        const int f = entries[i].second, g = entries[j].second;
        // Boxes must overlap; the pair is tested only in the cell of the overlap's low corner.
        const Eigen::RowVector3d ol = lo[f].cwiseMax(lo[g]), oh = hi[f].cwiseMin(hi[g]);
        if ((ol.array() > oh.array()).any()) continue;
        if (key(index(ol(0), 0), index(ol(1), 1), index(ol(2), 2)) != here) continue;
        int shared = 0, pf = -1, pg = -1;
        for (int p = 0; p < 3; ++p)
          for (int q = 0; q < 3; ++q)
            if (F(f, p) == F(g, q)) ++shared, pf = p, pg = q;
        if (shared >= 2) continue;
        const Eigen::Vector3d t[3] = {V.row(F(f, 0)), V.row(F(f, 1)), V.row(F(f, 2))};
        const Eigen::Vector3d u[3] = {V.row(F(g, 0)), V.row(F(g, 1)), V.row(F(g, 2))};
        const bool cross = shared == 0 ? TrianglesCross(t, u)
                                       : SegmentCrossesTriangle(t[(pf + 1) % 3], t[(pf + 2) % 3], u[0], u[1], u[2]) ||
                                             SegmentCrossesTriangle(u[(pg + 1) % 3], u[(pg + 2) % 3], t[0], t[1], t[2]);
        if (!cross) continue;
        ++out.pairs;
        out.faces.push_back(f);
        out.faces.push_back(g);
        if (out.examples.size() < maxExamples) out.examples.push_back({std::min(f, g), std::max(f, g)});
      }
    a = b;
  }
  std::sort(out.faces.begin(), out.faces.end());
  out.faces.erase(std::unique(out.faces.begin(), out.faces.end()), out.faces.end());
  return out;
}

std::vector<int> SelfIntersectingFaces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  return FindSelfIntersections(V, F, 0).faces;
}

}  // namespace colonmap::surface
