#include "Flattening/SplitBoundaryChords.h"

#include "Surface/MeshTopology.h"

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

namespace colonmap::flattening {

int SplitBoundaryChords(TriangleMesh& mesh) {
  std::vector<char> onBoundary(static_cast<std::size_t>(mesh.V.rows()), 0);
  for (const auto& loop : surface::BoundaryLoops(mesh.F))
    for (int v : loop) onBoundary[static_cast<std::size_t>(v)] = 1;
  // Interior edges with both ends on the boundary, in a fixed order (determinism).
  std::map<std::pair<int, int>, int> edgeFaces;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      ++edgeFaces[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<std::pair<int, int>> chords;
  for (const auto& [edge, count] : edgeFaces)
    if (count == 2 && onBoundary[edge.first] && onBoundary[edge.second]) chords.push_back(edge);
  if (chords.empty()) return 0;

  std::vector<Eigen::Vector3i> faces(static_cast<std::size_t>(mesh.F.rows()));
  std::vector<std::vector<int>> vertexFaces(static_cast<std::size_t>(mesh.V.rows()));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    faces[f] = mesh.F.row(f).transpose();
    for (int k = 0; k < 3; ++k) vertexFaces[mesh.F(f, k)].push_back(static_cast<int>(f));
  }
  const Eigen::Index n = mesh.V.rows(), k = static_cast<Eigen::Index>(chords.size());
  mesh.V.conservativeResize(n + k, 3);
  for (auto& [name, array] : mesh.pointData) array.values.conservativeResize(n + k, array.values.cols());
  vertexFaces.resize(static_cast<std::size_t>(n + k));

  for (Eigen::Index c = 0; c < k; ++c) {
    const auto [a, b] = chords[static_cast<std::size_t>(c)];
    const int m = static_cast<int>(n + c);
    mesh.V.row(m) = 0.5 * (mesh.V.row(a) + mesh.V.row(b));
    for (auto& [name, array] : mesh.pointData) {
      if (array.integer) array.values.row(m) = array.values.row(a);
      else array.values.row(m) = 0.5 * (array.values.row(a) + array.values.row(b));
    }
    // The (current) faces holding edge a-b; each (x, y, z) with x->y = a->b or b->a becomes
    // (x, m, z) and (m, y, z), keeping its orientation.
    std::vector<int> shared;
    for (int f : vertexFaces[a])
      if (std::find(vertexFaces[b].begin(), vertexFaces[b].end(), f) != vertexFaces[b].end()) shared.push_back(f);
    for (int f : shared) {
      Eigen::Vector3i& face = faces[static_cast<std::size_t>(f)];
      int r = 0;
      while (!((face[r] == a && face[(r + 1) % 3] == b) || (face[r] == b && face[(r + 1) % 3] == a))) ++r;
      const int x = face[r], y = face[(r + 1) % 3], z = face[(r + 2) % 3];
      face = Eigen::Vector3i(x, m, z);
      const int added = static_cast<int>(faces.size());
      faces.emplace_back(m, y, z);
      auto& yFaces = vertexFaces[y];
      yFaces.erase(std::remove(yFaces.begin(), yFaces.end(), f), yFaces.end());
      yFaces.push_back(added);
      vertexFaces[z].push_back(added);
      vertexFaces[m].push_back(f);
      vertexFaces[m].push_back(added);
    }
  }
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) mesh.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  mesh.cellData.clear();
  return static_cast<int>(k);
}

}  // namespace colonmap::flattening
