#pragma once
// Splitting mesh edges at their midpoints or at given points (the geometry does not change: the new vertex lies on
// the edge, each face on the edge becomes two coplanar halves with its orientation). Shared by
// SplitBoundaryChords and SplitNonDelaunayCutEdges. New vertices are appended in the order of
// `edges`, so existing vertex indices (cut paths, taeniae) stay valid. Point arrays get the mean
// of the edge's two ends (integer arrays: the first end's); cell arrays are dropped when
// anything was split.
#include "Core/TriangleMesh.h"

#include <utility>
#include <vector>

namespace colonmap::flattening {

// edges: vertex pairs joined by an edge of mesh, each at most once. Returns the new vertex of
// each edge (same order). Throws colonmap::Error when a pair is not an edge.
std::vector<int> SplitEdgesAtMidpoints(TriangleMesh& mesh, const std::vector<std::pair<int, int>>& edges);

// The same at a parameter per edge: the new vertex of edge (a, b) is (1 - t) a + t b (t in
// [0, 1]), point arrays interpolated alike (integer arrays: the nearer end's). Used to cut a mesh
// along a level set (RealColon/IsoLines.h).
std::vector<int> SplitEdgesAt(TriangleMesh& mesh, const std::vector<std::pair<int, int>>& edges,
                              const std::vector<double>& t);

}  // namespace colonmap::flattening
