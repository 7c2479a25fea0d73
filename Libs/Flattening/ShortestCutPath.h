#pragma once
// A cut path for a cylinder without a taenia: the shortest path along mesh edges (Euclidean
// edge lengths, Boost.Graph Dijkstra) from any vertex of one boundary loop to the other loop.
// Its inner vertices never touch either loop (a path that did could be shortened), so it is a
// valid input of CutAlongPath. Eigen in and out.
#include <Eigen/Core>

#include <vector>

namespace colonmap::flattening {

// V, F: the mesh; from, to: the two loops (vertex indices). Returns the vertices from a vertex
// of `from` to one of `to` (ties broken by the smallest index). Throws colonmap::Error when
// the loops are not connected.
Eigen::VectorXi ShortestCutPath(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& from,
                                const std::vector<int>& to);

}  // namespace colonmap::flattening
