#pragma once
// Splitting mesh edges at their midpoints (the geometry does not change: the new vertex lies on
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

}  // namespace colonmap::flattening
