#include "Landmarks/IsoLines.h"

#include "Flattening/SplitEdges.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <unordered_map>

namespace colonmap::landmarks {
namespace {

std::uint64_t EdgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

// Crossing parameter of the level on edge a -> b (f(a) and f(b) on different sides).
double Crossing(double fa, double fb, double level) { return (level - fa) / (fb - fa); }

}  // namespace

double LevelCurve::Length() const {
  double L = 0.0;
  for (Eigen::Index i = 1; i < points.rows(); ++i) L += (points.row(i) - points.row(i - 1)).norm();
  if (closed && points.rows() > 1) L += (points.row(0) - points.row(points.rows() - 1)).norm();
  return L;
}

std::vector<int> CutAtLevel(TriangleMesh& mesh, Eigen::VectorXd& f, double level) {
  std::vector<std::pair<int, int>> edges;
  std::vector<double> t;
  std::unordered_map<std::uint64_t, bool> seen;
  for (Eigen::Index face = 0; face < mesh.F.rows(); ++face)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(face, k), b = mesh.F(face, (k + 1) % 3);
      const double fa = f(a), fb = f(b);
      const bool strictly = (fa < level && fb > level) || (fa > level && fb < level);
      if (!strictly || !seen.emplace(EdgeKey(a, b), true).second) continue;
      edges.emplace_back(a, b);
      t.push_back(Crossing(fa, fb, level));
    }
  const Eigen::Index n = f.size();
  const std::vector<int> added = flattening::SplitEdgesAt(mesh, edges, t);
  f.conservativeResize(n + static_cast<Eigen::Index>(added.size()));
  for (int v : added) f(v) = level;
  return added;
}

std::vector<LevelCurve> LevelSet(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& f,
                                 double level) {
  // Each crossed face gives one segment between two crossed edges; edges link the segments.
  std::map<std::uint64_t, Eigen::RowVector3d> point;   // crossing point per crossed edge
  std::map<std::uint64_t, std::vector<std::uint64_t>> next;  // edge -> edges it shares a face segment with
  for (Eigen::Index face = 0; face < F.rows(); ++face) {
    std::uint64_t ends[2];
    int found = 0;
    for (int k = 0; k < 3 && found < 2; ++k) {
      const int a = F(face, k), b = F(face, (k + 1) % 3);
      if ((f(a) >= level) == (f(b) >= level)) continue;
      const std::uint64_t key = EdgeKey(a, b);
      const double w = Crossing(f(a), f(b), level);
      point.emplace(key, (1.0 - w) * V.row(a) + w * V.row(b));
      ends[found++] = key;
    }
    if (found != 2) continue;
    next[ends[0]].push_back(ends[1]);
    next[ends[1]].push_back(ends[0]);
  }
  std::vector<LevelCurve> curves;
  std::map<std::uint64_t, bool> used;
  // Open curves start at an edge with one neighbour (a boundary edge), loops anywhere.
  auto walk = [&](std::uint64_t start) {
    std::vector<Eigen::RowVector3d> pts;
    std::uint64_t prev = std::numeric_limits<std::uint64_t>::max(), cur = start;
    bool closed = false;
    while (true) {
      used[cur] = true;
      pts.push_back(point.at(cur));
      std::uint64_t go = std::numeric_limits<std::uint64_t>::max();
      for (std::uint64_t e : next[cur])
        if (e != prev && !used.count(e)) {
          go = e;
          break;
        }
      if (go == std::numeric_limits<std::uint64_t>::max()) {
        for (std::uint64_t e : next[cur])
          if (e == start && e != prev && pts.size() > 2) closed = true;
        break;
      }
      prev = cur;
      cur = go;
    }
    LevelCurve c;
    c.closed = closed;
    c.points.resize(static_cast<Eigen::Index>(pts.size()), 3);
    for (std::size_t i = 0; i < pts.size(); ++i) c.points.row(static_cast<Eigen::Index>(i)) = pts[i];
    curves.push_back(std::move(c));
  };
  for (const auto& [e, nb] : next)
    if (nb.size() == 1 && !used.count(e)) walk(e);
  for (const auto& [e, nb] : next)
    if (!used.count(e)) walk(e);
  return curves;
}

LevelSummary SummarizeLevels(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& f,
                             const Eigen::VectorXd& levels, const Eigen::Vector3d& down) {
  const Eigen::Index n = levels.size();
  LevelSummary s;
  Eigen::MatrixXd weighted = Eigen::MatrixXd::Zero(n, 3);
  s.length = Eigen::VectorXd::Zero(n);
  s.lowest = Eigen::MatrixXd::Constant(n, 3, std::numeric_limits<double>::quiet_NaN());
  Eigen::VectorXd depth = Eigen::VectorXd::Constant(n, -std::numeric_limits<double>::infinity());
  // Per face: the segments of every level between its smallest and largest corner value.
  struct Segment {
    Eigen::Index level;
    Eigen::Vector3d p, q;
  };
  std::vector<Segment> segments;
  for (Eigen::Index face = 0; face < F.rows(); ++face) {
    const int c[3] = {F(face, 0), F(face, 1), F(face, 2)};
    const double lo = std::min({f(c[0]), f(c[1]), f(c[2])}), hi = std::max({f(c[0]), f(c[1]), f(c[2])});
    // Levels with lo < level <= hi cross the face (a corner at the level counts as above).
    auto first = std::upper_bound(levels.data(), levels.data() + n, lo);
    for (auto it = first; it != levels.data() + n && *it <= hi; ++it) {
      const double level = *it;
      Eigen::Vector3d ends[2];
      int found = 0;
      for (int k = 0; k < 3 && found < 2; ++k) {
        const int a = c[k], b = c[(k + 1) % 3];
        if ((f(a) >= level) == (f(b) >= level)) continue;
        const double w = Crossing(f(a), f(b), level);
        ends[found++] = (1.0 - w) * V.row(a).transpose() + w * V.row(b).transpose();
      }
      if (found != 2) continue;
      const Eigen::Index li = it - levels.data();
      const double len = (ends[1] - ends[0]).norm();
      weighted.row(li) += len * 0.5 * (ends[0] + ends[1]).transpose();
      s.length(li) += len;
      for (const Eigen::Vector3d& e : ends)
        if (e.dot(down) > depth(li)) depth(li) = e.dot(down), s.lowest.row(li) = e.transpose();
      segments.push_back({li, ends[0], ends[1]});
    }
  }
  s.centroid = Eigen::MatrixXd::Constant(n, 3, std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index i = 0; i < n; ++i)
    if (s.length(i) > 0) s.centroid.row(i) = weighted.row(i) / s.length(i);
  Eigen::VectorXd radius = Eigen::VectorXd::Zero(n);
  s.maxRadius = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  for (const Segment& g : segments) {
    const Eigen::Vector3d c = s.centroid.row(g.level).transpose();
    radius(g.level) += (g.q - g.p).norm() * 0.5 * ((g.p - c).norm() + (g.q - c).norm());
    const double far = std::max((g.p - c).norm(), (g.q - c).norm());
    if (!(s.maxRadius(g.level) >= far)) s.maxRadius(g.level) = far;
  }
  s.meanRadius = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index i = 0; i < n; ++i)
    if (s.length(i) > 0) s.meanRadius(i) = radius(i) / s.length(i);
  return s;
}

}  // namespace colonmap::landmarks
