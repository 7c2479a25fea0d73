#pragma once
// Splits every interior edge whose two ends lie on the boundary (a "chord") at its midpoint.
// f1 is fixed (1 or 0) on each end loop, so a face whose three corners are all boundary
// vertices (the "ears" and "bridges" that cutting a surface along mesh edges leaves, as the
// landmarks stage does) would collapse to zero area in the flat map. Such a face always has a
// chord; the chord's midpoint is an interior vertex whose neighbours include the vertices across
// the chord, so f1 is free there and the new faces keep their area. Geometry is unchanged (the
// midpoint lies on the edge); new vertices are appended, so existing vertex indices (cut paths)
// stay valid. Point arrays get the mean of the chord's two ends (integer arrays: the first end's).
#include "Core/TriangleMesh.h"

namespace colonmap::flattening {

// Returns the number of chords split. Cell arrays are dropped when anything was split.
int SplitBoundaryChords(TriangleMesh& mesh);

}  // namespace colonmap::flattening
