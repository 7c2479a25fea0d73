#pragma once
// A segment file (segment_<X>.vtp of a landmarks folder, flat_<X>.vtp of a flattening folder)
// holds the segment its name says (issue 24: two files swapped by hand registered with 76 mm mean
// error). ColonLandmarks writes each segment's index into the SegmentId point array.
#include "Core/TriangleMesh.h"

#include <string>

namespace colonmap::io {

// Throws colonmap::InputError ("<what> '<path>': holds segment T (SegmentId 1), not D") when the
// mesh's SegmentId array names another of the five segments (0..4 = A, T, D, S, R) than `id`.
// A mesh without the array passes (older files, other tools).
void CheckSegmentId(const TriangleMesh& mesh, int id, const std::string& what, const std::string& path);

}  // namespace colonmap::io
