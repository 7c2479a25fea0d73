#pragma once
// Cutting a topological cylinder open along a vertex path (DESIGN §2.3): the path's vertices
// are duplicated so that the cut surface is a topological disk whose boundary runs
// g1 + side 1 + g2 + side 0. Eigen in and out, libigl style.
#include <Eigen/Core>

namespace colonmap::flattening {

struct CutMesh {
  Eigen::MatrixXd V;         // n' x 3: the input vertices, then one copy of each path vertex
  Eigen::MatrixXi F;         // m x 3: same faces in the same order, path corners re-indexed
  Eigen::VectorXi original;  // n': input vertex index of each cut-mesh vertex
  // n': -1 off the path; 0 for the copy kept by the faces on the LEFT of the directed path
  // (the faces that traverse a path edge p_k -> p_k+1 in their own vertex order: they keep the
  // original index), 1 for the new copy used by the faces on its right.
  Eigen::VectorXi side;
};

// Cuts (V, F) along path = p_0 .. p_k (vertex indices; consecutive ones joined by a mesh edge;
// p_0 and p_k on the boundary, the others interior, no vertex twice). The copies of p_i on the
// right side get indices n + i. Throws colonmap::Error (a sentence without the input's name)
// when the path is not such a path.
CutMesh CutAlongPath(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXi& path);

}  // namespace colonmap::flattening
