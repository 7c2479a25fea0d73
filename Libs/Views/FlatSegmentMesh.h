#pragma once
// One segment of a registration mesh (issue 8): registration.vtp and registration_prone.vtp hold
// the cut surfaces of all segments in one mesh, point data SegmentId (0..4 = A..R). This picks
// segment `id`: its vertices (in order), its faces (those whose three corners are in the
// segment, reindexed) and the rows of any per-vertex array. Eigen and Core in and out.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

#include <string>

namespace colonmap::views {

struct FlatSegmentMesh {
  Eigen::VectorXi vertices;  // indices into the whole mesh, increasing
  Eigen::VectorXi faces;     // indices into the whole mesh's faces, increasing
  Eigen::MatrixXi F;         // faces with local vertex indices (rows of `vertices`)

  // Rows of a whole-mesh per-vertex (or per-face) array for this segment.
  Eigen::MatrixXd PointRows(const Eigen::MatrixXd& whole) const;
  Eigen::MatrixXd FaceRows(const Eigen::MatrixXd& whole) const;
};

// Throws colonmap::Error (naming `what`) when the mesh has no integer-valued SegmentId point
// array, or when a face joins two segments.
FlatSegmentMesh ExtractSegment(const TriangleMesh& mesh, int id, const std::string& what);

// A named point (or cell) array of `mesh` with `cols` components, or colonmap::Error naming
// `what` and the array.
const Eigen::MatrixXd& PointArray(const TriangleMesh& mesh, const std::string& name, int cols, const std::string& what);
const Eigen::MatrixXd& CellArray(const TriangleMesh& mesh, const std::string& name, int cols, const std::string& what);

}  // namespace colonmap::views
