#include "Flattening/SplitEdges.h"

#include "Core/Error.h"

#include <algorithm>
#include <cstdint>
#include <unordered_map>
#include <string>

namespace colonmap::flattening {

std::vector<int> SplitEdgesAtMidpoints(TriangleMesh& mesh, const std::vector<std::pair<int, int>>& edges) {
  return SplitEdgesAt(mesh, edges, std::vector<double>(edges.size(), 0.5));
}

std::vector<int> SplitEdgesAt(TriangleMesh& mesh, const std::vector<std::pair<int, int>>& edges,
                              const std::vector<double>& t) {
  if (t.size() != edges.size()) throw Error("split edges: one parameter per edge expected");
  std::vector<int> added;
  if (edges.empty()) return added;
  auto key = [](int a, int b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
  };
  // The faces on each requested edge (one pass over the faces), kept up to date while splitting.
  std::unordered_map<std::uint64_t, std::vector<int>> edgeFaces;
  for (const auto& [a, b] : edges) edgeFaces[key(a, b)];
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (auto it = edgeFaces.find(key(mesh.F(f, k), mesh.F(f, (k + 1) % 3))); it != edgeFaces.end())
        it->second.push_back(static_cast<int>(f));
  std::vector<Eigen::Vector3i> faces(static_cast<std::size_t>(mesh.F.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) faces[f] = mesh.F.row(f).transpose();
  const Eigen::Index n = mesh.V.rows(), k = static_cast<Eigen::Index>(edges.size());
  mesh.V.conservativeResize(n + k, 3);
  for (auto& [name, array] : mesh.pointData) array.values.conservativeResize(n + k, array.values.cols());

  for (Eigen::Index c = 0; c < k; ++c) {
    const auto [a, b] = edges[static_cast<std::size_t>(c)];
    const int m = static_cast<int>(n + c);
    added.push_back(m);
    const double w = t[static_cast<std::size_t>(c)];
    mesh.V.row(m) = (1.0 - w) * mesh.V.row(a) + w * mesh.V.row(b);
    for (auto& [name, array] : mesh.pointData) {
      if (array.integer) array.values.row(m) = array.values.row(w <= 0.5 ? a : b);
      else array.values.row(m) = (1.0 - w) * array.values.row(a) + w * array.values.row(b);
    }
    const std::vector<int> shared = edgeFaces[key(a, b)];
    if (shared.empty())
      throw Error("split edges: vertices " + std::to_string(a) + " and " + std::to_string(b) + " share no face");
    // Each face (x, y, z) with x->y = a->b or b->a becomes (x, m, z) and (m, y, z), keeping its
    // orientation; a requested edge y-z moves to the new face.
    for (int f : shared) {
      Eigen::Vector3i& face = faces[static_cast<std::size_t>(f)];
      int r = 0;
      while (!((face[r] == a && face[(r + 1) % 3] == b) || (face[r] == b && face[(r + 1) % 3] == a))) ++r;
      const int x = face[r], y = face[(r + 1) % 3], z = face[(r + 2) % 3];
      face = Eigen::Vector3i(x, m, z);
      const int fresh = static_cast<int>(faces.size());
      faces.emplace_back(m, y, z);
      if (auto it = edgeFaces.find(key(y, z)); it != edgeFaces.end())
        std::replace(it->second.begin(), it->second.end(), f, fresh);
    }
  }
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) mesh.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  mesh.cellData.clear();
  return added;
}

}  // namespace colonmap::flattening
