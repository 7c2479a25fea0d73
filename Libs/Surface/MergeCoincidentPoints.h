#pragma once
// Points of a triangle mesh that lie within a tolerance of each other merged into one, the same
// way on every run: points are visited in index order, and each one not yet merged keeps its
// place and takes every later unmerged point within `tolerance` (the lowest index wins). Faces
// are kept in their order with their corners renumbered (a face whose corners merged keeps its
// repeated corner: the caller decides about such degenerate faces); the points that remain keep
// their order and coordinates. Why not vtkStaticCleanPolyData: in VTK 9.1 its merge with a
// tolerance runs on several threads that race for the same points, so the welded HuBMAP colon
// (and every real-colon phantom made from it) differed between runs of the same command.
// `mergedInto` (optional): per input point, its index in the output.
#include "Core/TriangleMesh.h"

#include <vector>

namespace colonmap::surface {

TriangleMesh MergeCoincidentPoints(const TriangleMesh& mesh, double tolerance, std::vector<int>* mergedInto = nullptr);

}  // namespace colonmap::surface
