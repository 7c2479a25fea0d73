#pragma once
// Half-edge adjacency of a triangle list in linear time (bucketed by the smaller end, no global
// sort), for the flattening's fast topology check and intrinsic Delaunay flips. Half-edge
// h = 3 f + k runs F(f,k) -> F(f,(k+1)%3).
#include <Eigen/Core>

#include <vector>

namespace colonmap::flattening {

struct HalfEdgeTwins {
  std::vector<int> twin;       // 3m: the opposite half-edge, -1 on the boundary (or when unmatched)
  long edges = 0;              // undirected edges
  long nonManifoldEdges = 0;   // edges with more than two faces (their half-edges left unmatched)
  long inconsistentEdges = 0;  // edges whose two faces run them the same way (left unmatched)
};
// n: number of vertices (indices in F are < n).
HalfEdgeTwins MatchHalfEdges(const Eigen::MatrixXi& F, Eigen::Index n);

// A fast cylinder check (what ConformalFlattening needs): one component, manifold, consistently
// oriented, Euler characteristic 0, two boundary loops, each boundary vertex on one loop once.
// On success loops holds the two loops as surface::BoundaryLoops gives them (each from its
// smallest vertex, in the direction of its faces, the loop with the smaller first vertex first).
bool IsCylinder(const Eigen::MatrixXi& F, Eigen::Index n, std::vector<std::vector<int>>& loops);

}  // namespace colonmap::flattening
