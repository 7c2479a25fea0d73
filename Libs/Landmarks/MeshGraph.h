#pragma once
// Shortest paths along the edges of a triangle mesh, for the geodesic extremities of the colon
// tube, its geodesic distance field and taenia paths along edges (Analysis/ShortestPaths.h).
#include "Analysis/ShortestPaths.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::landmarks {

using analysis::EdgeGraph;
using analysis::PathTo;
using analysis::ShortestPaths;

// The undirected edges of F (each once, a < b) and their Euclidean lengths in V.
EdgeGraph MeshEdgeGraph(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace colonmap::landmarks
