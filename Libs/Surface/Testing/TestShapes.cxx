#include "TestShapes.h"

#include <Eigen/Geometry>

#include <cmath>
#include <map>
#include <utility>
#include <vector>

namespace colonmap::surface::testing {
namespace {
constexpr double kPi = 3.14159265358979323846;

TriangleMesh FromLists(const std::vector<Eigen::Vector3d>& v, const std::vector<Eigen::Vector3i>& f) {
  TriangleMesh m;
  m.V.resize(static_cast<Eigen::Index>(v.size()), 3);
  m.F.resize(static_cast<Eigen::Index>(f.size()), 3);
  for (std::size_t i = 0; i < v.size(); ++i) m.V.row(static_cast<Eigen::Index>(i)) = v[i].transpose();
  for (std::size_t i = 0; i < f.size(); ++i) m.F.row(static_cast<Eigen::Index>(i)) = f[i].transpose();
  return m;
}
}  // namespace

TriangleMesh Icosphere(double r, int levels) {
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Eigen::Vector3i> f = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                    {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                    {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& p : v) p.normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<int, int>, int> mid;
    auto middle = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      v.push_back((v[a] + v[b]).normalized());
      return mid[key] = static_cast<int>(v.size()) - 1;
    };
    std::vector<Eigen::Vector3i> g;
    for (const auto& q : f) {
      const int a = middle(q[0], q[1]), b = middle(q[1], q[2]), c = middle(q[2], q[0]);
      g.push_back({q[0], a, c});
      g.push_back({q[1], b, a});
      g.push_back({q[2], c, b});
      g.push_back({a, b, c});
    }
    f = std::move(g);
  }
  for (auto& p : v) p *= r;
  return FromLists(v, f);
}

TriangleMesh Torus(double R, double a, int n, int m) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * kPi * i / n, w = 2 * kPi * j / m;
      v.emplace_back((R + a * std::cos(w)) * std::cos(u), (R + a * std::cos(w)) * std::sin(u), a * std::sin(w));
    }
  auto id = [&](int i, int j) { return ((i + n) % n) * m + (j + m) % m; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return FromLists(v, f);
}

TriangleMesh OpenCylinder(double r, double h, int n, int m) {
  std::vector<Eigen::Vector3d> v;
  std::vector<Eigen::Vector3i> f;
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j < n; ++j) {
      const double w = 2 * kPi * (j + 0.5 * (i % 2)) / n;
      v.emplace_back(r * std::cos(w), r * std::sin(w), h * i / m);
    }
  auto id = [&](int i, int j) { return i * n + (j + n) % n; };
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      if (i % 2 == 0) {
        f.push_back({id(i, j), id(i, j + 1), id(i + 1, j)});
        f.push_back({id(i, j + 1), id(i + 1, j + 1), id(i + 1, j)});
      } else {
        f.push_back({id(i, j), id(i, j + 1), id(i + 1, j + 1)});
        f.push_back({id(i, j), id(i + 1, j + 1), id(i + 1, j)});
      }
    }
  return FromLists(v, f);
}

}  // namespace colonmap::surface::testing
