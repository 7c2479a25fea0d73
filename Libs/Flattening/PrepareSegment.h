#pragma once
// Preparing one colon segment (a cylinder and its cut path) for ConformalFlattening with the
// intrinsic Delaunay Laplacian. Two steps that add vertices on existing edges only (the surface
// does not move; new vertices are appended, so the old indices stay valid):
//  - SplitBoundaryChords: faces with three end-loop corners would collapse (see that header).
//  - SplitNonDelaunayKeptEdges: the intrinsic Delaunay flips keep some edges: the cut path's (the
//    cut must stay a chain of edges) and those whose flip would make a chord or a non-simplicial
//    triangulation (IntrinsicDelaunay.h). Such an edge opposite two wide angles keeps a negative
//    cotangent weight, the one place where the discrete maximum principle (and with it the
//    fold-free guarantee) would fail. Those that are edges of the mesh are split at their
//    midpoints and the test repeated (Steiner points, as in constrained Delaunay refinement).
//    Measured on the phantom pipeline's segments: 6-35 cut-path edges and 2-5 edges next to
//    the end loops per segment; none left after the rounds.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

namespace colonmap::flattening {

// mesh: the cylinder; path: its cut (vertex ids, updated: each split path edge gets its midpoint
// inserted). Point arrays as in SplitEdges.h. At most `rounds` rounds of splitting. Returns the
// number of edges split; *left (optional): interior edges still negative after the last round
// (split or not: an edge made by flips is not an edge of the mesh and is not split).
int SplitNonDelaunayKeptEdges(TriangleMesh& mesh, Eigen::VectorXi& path, int rounds = 4, int* left = nullptr);

struct PreparedSegment {
  int boundaryChords = 0;  // SplitBoundaryChords
  int splitEdges = 0;      // SplitNonDelaunayKeptEdges
  int negativeLeft = 0;
};
// Both steps, in that order.
PreparedSegment PrepareSegment(TriangleMesh& mesh, Eigen::VectorXi& path);

}  // namespace colonmap::flattening
