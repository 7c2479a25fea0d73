#pragma once
// Shortest paths along the edges of a triangle mesh (Boost.Graph Dijkstra), for the geodesic
// extremities of the colon tube, its geodesic distance field and taenia paths along edges.
// Eigen in, std out; Boost stays in the .cxx.
#include <Eigen/Core>

#include <vector>

namespace colonmap::landmarks {

// The undirected edges of F (each once, a < b) and their Euclidean lengths in V.
struct EdgeGraph {
  int vertices = 0;
  std::vector<std::pair<int, int>> edges;
  std::vector<double> lengths;
};
EdgeGraph MeshEdgeGraph(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Dijkstra from a set of source vertices (distance 0 each). weights: one per edge of g (the
// edge lengths when null). Returns the distance of every vertex (infinity when unreachable);
// predecessor (optional) gets each vertex's previous vertex on its shortest path (itself for
// sources and unreachable vertices).
std::vector<double> ShortestPaths(const EdgeGraph& g, const std::vector<int>& sources,
                                  const std::vector<double>* weights = nullptr,
                                  std::vector<int>* predecessor = nullptr);

// The vertex path from a source to `target` read off a predecessor array (source first).
std::vector<int> PathTo(const std::vector<int>& predecessor, int target);

}  // namespace colonmap::landmarks
