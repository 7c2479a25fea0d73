#pragma once
// What ITK's NRRD reader lets through (issue 24), checked on the text header before the file is
// read: a NaN spacing, direction or origin, which ITK takes as "unknown" and silently replaces by
// 1 mm or identity, or an infinite one (a measurement would then be wrong without a word). Only
// .nrrd and .nhdr; other paths return at once.
#include <string>
#include <vector>

namespace colonmap::io {

// Throws colonmap::InputError (naming `what` and `path`) when "spacings:", "space directions:" or
// "space origin:" holds NaN or an infinite number ("inf", "1e999"), or when raw voxel data (after
// the header, or in the detached "data file:") is shorter than "sizes:" and "type:" promise. Returns the axes (1-based,
// among the first three) "spacings:" gives a negative spacing: ITK reads them as positive
// spacings along flipped axes, silently.
std::vector<int> CheckNrrdHeader(const std::string& path, const std::string& what);

}  // namespace colonmap::io
