#pragma once
// Midpoint subdivision of a triangle mesh: every face becomes four at its edge midpoints, the
// surface does not move (the new vertices lie on the old edges, the four faces are coplanar with
// the old one and keep its orientation and, up to scale, its shape).
//
// Why, before flattening: the Beltrami coefficient |mu| of a piecewise-linear map falls in
// proportion to the edge length on a given surface. Measured on the real GCA colon (200K faces
// from a 1.5 mm grid, segments of 35-69K faces): mean |mu| 0.020-0.028, after one level
// 0.010-0.014, while decimating the same colon to 400K faces instead made it worse (0.021-0.032:
// the finer mesh follows the voxel steps that the 200K one had smoothed away).
//
// Old vertices keep their indices; one vertex per edge is appended. Point arrays get the mean of
// the edge's two ends (integer arrays: the end with the smaller index), as in SplitEdges.h; cell
// arrays are dropped.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

namespace colonmap::flattening {

// levels: subdivisions applied in turn (0: nothing). path (optional): vertices joined by mesh
// edges (a cut path); each of its edges gets its midpoint inserted, so it stays a chain of edges
// from the same first to the same last vertex. Throws colonmap::Error when two consecutive path
// vertices share no edge.
void MidpointSubdivision(TriangleMesh& mesh, Eigen::VectorXi* path = nullptr, int levels = 1);

}  // namespace colonmap::flattening
