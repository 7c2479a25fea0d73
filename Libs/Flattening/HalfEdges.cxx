#include "Flattening/HalfEdges.h"

#include <algorithm>
#include <numeric>

namespace colonmap::flattening {

HalfEdgeTwins MatchHalfEdges(const Eigen::MatrixXi& F, Eigen::Index n) {
  const int H = static_cast<int>(3 * F.rows());
  HalfEdgeTwins r;
  r.twin.assign(H, -1);
  auto from = [&F](int h) { return F(h / 3, h % 3); };
  auto to = [&F](int h) { return F(h / 3, (h % 3 + 1) % 3); };
  // Buckets by the smaller end (counting sort), then matching within each small bucket.
  std::vector<int> start(static_cast<std::size_t>(n) + 1, 0), order(H);
  for (int h = 0; h < H; ++h) ++start[std::min(from(h), to(h)) + 1];
  std::partial_sum(start.begin(), start.end(), start.begin());
  std::vector<int> fill(start.begin(), start.end() - 1);
  for (int h = 0; h < H; ++h) order[fill[std::min(from(h), to(h))]++] = h;
  for (Eigen::Index v = 0; v < n; ++v) {
    const int b = start[v], e = start[v + 1];
    for (int i = b; i < e; ++i) {
      const int h = order[i];
      if (h < 0) continue;
      const int other = std::max(from(h), to(h));
      // All half-edges of this edge in the bucket.
      int count = 1, match = -1;
      for (int j = i + 1; j < e; ++j) {
        const int g = order[j];
        if (g >= 0 && std::max(from(g), to(g)) == other) {
          ++count;
          match = match < 0 ? j : match;
        }
      }
      ++r.edges;
      if (count == 2) {
        const int g = order[match];
        if (from(g) == to(h)) {
          r.twin[h] = g;
          r.twin[g] = h;
        } else {
          ++r.inconsistentEdges;
        }
      } else if (count > 2) {
        ++r.nonManifoldEdges;
      }
      // Mark the edge's half-edges done.
      for (int j = i + 1; j < e; ++j)
        if (order[j] >= 0 && std::max(from(order[j]), to(order[j])) == other) order[j] = -1;
    }
  }
  return r;
}

bool IsCylinder(const Eigen::MatrixXi& F, Eigen::Index n, std::vector<std::vector<int>>& loops) {
  loops.clear();
  const HalfEdgeTwins t = MatchHalfEdges(F, n);
  if (t.nonManifoldEdges || t.inconsistentEdges) return false;
  const int m = static_cast<int>(F.rows());
  // One component (union-find over faces through shared edges).
  std::vector<int> parent(m);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&parent](int a) {
    while (parent[a] != a) a = parent[a] = parent[parent[a]];
    return a;
  };
  for (int h = 0; h < 3 * m; ++h)
    if (t.twin[h] > h) parent[find(h / 3)] = find(t.twin[h] / 3);
  for (int f = 1; f < m; ++f)
    if (find(f) != find(0)) return false;
  // Boundary: exactly one outgoing boundary half-edge per boundary vertex.
  std::vector<int> next(static_cast<std::size_t>(n), -1);
  std::vector<char> used(static_cast<std::size_t>(n), 0);
  for (int h = 0; h < 3 * m; ++h) {
    used[F(h / 3, h % 3)] = 1;
    if (t.twin[h] >= 0) continue;
    const int a = F(h / 3, h % 3), b = F(h / 3, (h % 3 + 1) % 3);
    if (next[a] >= 0) return false;  // two boundary fans meet at a
    next[a] = b;
  }
  const long vertices = std::count(used.begin(), used.end(), 1);
  if (vertices - t.edges + m != 0) return false;
  std::vector<char> seen(static_cast<std::size_t>(n), 0);
  for (Eigen::Index v = 0; v < n; ++v) {
    if (next[v] < 0 || seen[v]) continue;
    std::vector<int> loop;
    for (int at = static_cast<int>(v); !seen[at]; at = next[at]) {
      if (next[at] < 0) return false;
      seen[at] = 1;
      loop.push_back(at);
    }
    if (loop.front() != next[loop.back()]) return false;
    loops.push_back(std::move(loop));
    if (loops.size() > 2) return false;
  }
  return loops.size() == 2;
}

}  // namespace colonmap::flattening
