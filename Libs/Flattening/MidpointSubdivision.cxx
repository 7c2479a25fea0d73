#include "Flattening/MidpointSubdivision.h"

#include "Core/Error.h"

#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace colonmap::flattening {

namespace {

std::uint64_t EdgeKey(int a, int b) {
  if (a > b) std::swap(a, b);
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(a)) << 32) | static_cast<std::uint32_t>(b);
}

void SubdivideOnce(TriangleMesh& mesh, Eigen::VectorXi* path) {
  const Eigen::Index n = mesh.V.rows(), m = mesh.F.rows();
  // Vertex ids are int: n + (at most 3m) midpoints, and 4m faces, must fit.
  if (static_cast<double>(n) + 3.0 * static_cast<double>(m) > static_cast<double>(std::numeric_limits<int>::max()) ||
      4.0 * static_cast<double>(m) > static_cast<double>(std::numeric_limits<int>::max()))
    throw Error("midpoint subdivision: " + std::to_string(m) + " faces are too many to subdivide");
  // One midpoint per edge, numbered in order of first appearance (deterministic).
  std::unordered_map<std::uint64_t, int> midpoint;
  midpoint.reserve(static_cast<std::size_t>(2 * m));
  std::vector<std::pair<int, int>> ends;
  Eigen::MatrixXi mid(m, 3);  // mid(f, k): midpoint of edge F(f,k) -> F(f,k+1)
  for (Eigen::Index f = 0; f < m; ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = mesh.F(f, k), b = mesh.F(f, (k + 1) % 3);
      const auto [it, fresh] = midpoint.emplace(EdgeKey(a, b), static_cast<int>(n + static_cast<Eigen::Index>(ends.size())));
      if (fresh) ends.emplace_back(std::min(a, b), std::max(a, b));
      mid(f, k) = it->second;
    }
  // The path first, so that a bad one leaves the mesh as it was.
  if (path && path->size() > 1) {
    Eigen::VectorXi p(2 * path->size() - 1);
    for (Eigen::Index i = 0; i + 1 < path->size(); ++i) {
      const auto it = midpoint.find(EdgeKey((*path)(i), (*path)(i + 1)));
      if (it == midpoint.end())
        throw Error("midpoint subdivision: path vertices " + std::to_string((*path)(i)) + " and " +
                    std::to_string((*path)(i + 1)) + " share no edge");
      p(2 * i) = (*path)(i);
      p(2 * i + 1) = it->second;
    }
    p(p.size() - 1) = (*path)(path->size() - 1);
    *path = std::move(p);
  }
  const Eigen::Index e = static_cast<Eigen::Index>(ends.size());
  mesh.V.conservativeResize(n + e, 3);
  for (auto& [name, array] : mesh.pointData) array.values.conservativeResize(n + e, array.values.cols());
  for (Eigen::Index c = 0; c < e; ++c) {
    const auto [a, b] = ends[static_cast<std::size_t>(c)];
    mesh.V.row(n + c) = 0.5 * (mesh.V.row(a) + mesh.V.row(b));
    for (auto& [name, array] : mesh.pointData)
      array.values.row(n + c) = array.integer ? Eigen::RowVectorXd(array.values.row(a))
                                              : Eigen::RowVectorXd(0.5 * (array.values.row(a) + array.values.row(b)));
  }
  // Corner faces (a, ab, ca), ... then the middle face (ab, bc, ca): same orientation.
  Eigen::MatrixXi F(4 * m, 3);
  for (Eigen::Index f = 0; f < m; ++f) {
    const int a = mesh.F(f, 0), b = mesh.F(f, 1), c = mesh.F(f, 2);
    const int ab = mid(f, 0), bc = mid(f, 1), ca = mid(f, 2);
    F.row(4 * f) << a, ab, ca;
    F.row(4 * f + 1) << ab, b, bc;
    F.row(4 * f + 2) << ca, bc, c;
    F.row(4 * f + 3) << ab, bc, ca;
  }
  mesh.F = std::move(F);
  mesh.cellData.clear();
}

}  // namespace

void MidpointSubdivision(TriangleMesh& mesh, Eigen::VectorXi* path, int levels) {
  for (int l = 0; l < levels; ++l) SubdivideOnce(mesh, path);
}

}  // namespace colonmap::flattening
