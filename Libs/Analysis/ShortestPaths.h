#pragma once
// Shortest paths on a weighted undirected graph (Boost.Graph Dijkstra), for geodesics along
// mesh edges (Landmarks/MeshGraph.h) and through voxel grids (Segmentation/PieceEnds.h).
// std in and out; Boost stays in the .cxx.
#include <memory>
#include <utility>
#include <vector>

namespace colonmap::analysis {

// Undirected edges (each once) and their lengths.
struct EdgeGraph {
  int vertices = 0;
  std::vector<std::pair<int, int>> edges;
  std::vector<double> lengths;
};

// Dijkstra from a set of source vertices (distance 0 each). weights: one per edge of g (the
// edge lengths when null). Returns the distance of every vertex (infinity when unreachable);
// predecessor (optional) gets each vertex's previous vertex on its shortest path (itself for
// sources and unreachable vertices).
std::vector<double> ShortestPaths(const EdgeGraph& g, const std::vector<int>& sources,
                                  const std::vector<double>* weights = nullptr,
                                  std::vector<int>* predecessor = nullptr);

// The same graph prepared once for many single-source runs (the CSR graph is sorted once).
class ShortestPathGraph {
 public:
  explicit ShortestPathGraph(const EdgeGraph& g);
  ~ShortestPathGraph();
  ShortestPathGraph(const ShortestPathGraph&) = delete;
  ShortestPathGraph& operator=(const ShortestPathGraph&) = delete;
  // Distance of every vertex from `source` (infinity when unreachable).
  std::vector<double> From(int source) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The vertex path from a source to `target` read off a predecessor array (source first).
std::vector<int> PathTo(const std::vector<int>& predecessor, int target);

}  // namespace colonmap::analysis
