#include "Views/FlatSegmentMesh.h"

#include "Core/Error.h"

#include <cmath>
#include <vector>

namespace colonmap::views {

Eigen::MatrixXd FlatSegmentMesh::PointRows(const Eigen::MatrixXd& whole) const {
  Eigen::MatrixXd out(vertices.size(), whole.cols());
  for (Eigen::Index k = 0; k < vertices.size(); ++k) out.row(k) = whole.row(vertices(k));
  return out;
}

Eigen::MatrixXd FlatSegmentMesh::FaceRows(const Eigen::MatrixXd& whole) const {
  Eigen::MatrixXd out(faces.size(), whole.cols());
  for (Eigen::Index k = 0; k < faces.size(); ++k) out.row(k) = whole.row(faces(k));
  return out;
}

const Eigen::MatrixXd& PointArray(const TriangleMesh& mesh, const std::string& name, int cols, const std::string& what) {
  const auto it = mesh.pointData.find(name);
  if (it == mesh.pointData.end() || it->second.values.cols() != cols || it->second.values.rows() != mesh.V.rows())
    throw Error(what + ": needs point data " + name + " with " + std::to_string(cols) + " components");
  return it->second.values;
}

const Eigen::MatrixXd& CellArray(const TriangleMesh& mesh, const std::string& name, int cols, const std::string& what) {
  const auto it = mesh.cellData.find(name);
  if (it == mesh.cellData.end() || it->second.values.cols() != cols || it->second.values.rows() != mesh.F.rows())
    throw Error(what + ": needs cell data " + name + " with " + std::to_string(cols) + " components");
  return it->second.values;
}

FlatSegmentMesh ExtractSegment(const TriangleMesh& mesh, int id, const std::string& what) {
  const Eigen::MatrixXd& seg = PointArray(mesh, "SegmentId", 1, what);
  std::vector<int> local(static_cast<std::size_t>(mesh.V.rows()), -1);
  std::vector<int> verts, faces;
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i)
    if (std::lround(seg(i, 0)) == id) {
      local[static_cast<std::size_t>(i)] = static_cast<int>(verts.size());
      verts.push_back(static_cast<int>(i));
    }
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    int in = 0;
    for (int k = 0; k < 3; ++k) in += local[static_cast<std::size_t>(mesh.F(f, k))] >= 0;
    if (in == 3) faces.push_back(static_cast<int>(f));
    else if (in > 0) throw Error(what + ": face " + std::to_string(f) + " joins two segments");
  }
  FlatSegmentMesh s;
  s.vertices = Eigen::Map<Eigen::VectorXi>(verts.data(), static_cast<Eigen::Index>(verts.size()));
  s.faces = Eigen::Map<Eigen::VectorXi>(faces.data(), static_cast<Eigen::Index>(faces.size()));
  s.F.resize(s.faces.size(), 3);
  for (Eigen::Index k = 0; k < s.faces.size(); ++k)
    for (int c = 0; c < 3; ++c) s.F(k, c) = local[static_cast<std::size_t>(mesh.F(s.faces(k), c))];
  return s;
}

}  // namespace colonmap::views
