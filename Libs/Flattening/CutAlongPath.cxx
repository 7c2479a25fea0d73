#include "Flattening/CutAlongPath.h"

#include "Core/Error.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::flattening {
namespace {

int Find(std::vector<int>& parent, int a) {
  while (parent[a] != a) a = parent[a] = parent[parent[a]];
  return a;
}

}  // namespace

CutMesh CutAlongPath(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& path) {
  const int n = static_cast<int>(V.rows());
  const int k = static_cast<int>(path.size());
  if (k < 2) throw Error("the cut path has fewer than two vertices");
  std::vector<int> position(n, -1);  // index of each vertex in the path
  for (int i = 0; i < k; ++i) {
    if (path(i) < 0 || path(i) >= n) throw Error("the cut path has a vertex index out of range");
    if (position[path(i)] >= 0) throw Error("the cut path visits vertex " + std::to_string(path(i)) + " twice");
    position[path(i)] = i;
  }
  // Faces at each path vertex (only those are re-indexed).
  std::vector<std::vector<int>> faces(k);
  for (int f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      if (position[F(f, c)] >= 0) faces[position[F(f, c)]].push_back(f);
  auto isCutEdge = [&](int a, int b) {
    const int pa = position[a], pb = position[b];
    return pa >= 0 && pb >= 0 && std::abs(pa - pb) == 1;
  };

  CutMesh cut;
  cut.V.resize(n + k, 3);
  cut.V.topRows(n) = V;
  cut.F = F;
  cut.original.resize(n + k);
  std::iota(cut.original.data(), cut.original.data() + n, 0);
  cut.side = Eigen::VectorXi::Constant(n + k, -1);
  for (int i = 0; i < k; ++i) {
    const int p = path(i);
    cut.V.row(n + i) = V.row(p);
    cut.original(n + i) = p;
    cut.side(p) = 0;
    cut.side(n + i) = 1;
    // Group the faces around p: two faces are in one group when they share an edge (p, q)
    // that is not on the path. The path edges at p split its fan into exactly two groups.
    const std::vector<int>& fs = faces[i];
    std::vector<int> parent(fs.size());
    std::iota(parent.begin(), parent.end(), 0);
    std::map<int, int> firstWithNeighbour;  // q -> local face using edge (p, q)
    int leftFace = -1;                      // a face left of the directed path edge at p
    for (int a = 0; a < static_cast<int>(fs.size()); ++a) {
      const int f = fs[a];
      for (int c = 0; c < 3; ++c) {
        const int u = F(f, c), w = F(f, (c + 1) % 3);  // directed edge u -> w of face f
        if (u == p || w == p) {
          const int q = u == p ? w : u;
          if (isCutEdge(p, q)) {
            // Left of p_j -> p_j+1 means the face runs the edge in the path direction.
            if (position[u] + 1 == position[w]) leftFace = a;
            continue;
          }
          auto [it, fresh] = firstWithNeighbour.emplace(q, a);
          if (!fresh) parent[Find(parent, a)] = Find(parent, it->second);
        }
      }
    }
    if (leftFace < 0)
      throw Error("the cut path runs along the boundary or between vertices without a shared edge near vertex " +
                  std::to_string(p));
    std::set<int> groups;
    for (int a = 0; a < static_cast<int>(fs.size()); ++a) groups.insert(Find(parent, a));
    if (groups.size() != 2)
      throw Error("the cut path does not split the faces at vertex " + std::to_string(p) + " into two sides (" +
                  std::to_string(groups.size()) + " groups: does it touch the boundary in between?)");
    const int left = Find(parent, leftFace);
    for (int a = 0; a < static_cast<int>(fs.size()); ++a) {
      if (Find(parent, a) == left) continue;
      for (int c = 0; c < 3; ++c)
        if (cut.F(fs[a], c) == p) cut.F(fs[a], c) = n + i;
    }
  }
  return cut;
}

}  // namespace colonmap::flattening
