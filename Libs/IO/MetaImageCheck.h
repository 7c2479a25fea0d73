#pragma once
// What ITK's MetaImage reader lets through (issue 24), checked on the header before the file is
// read: voxel data shorter than DimSize x ElementType says (MetaIO prints two lines on stderr and
// ITK returns a partial image). Only .mha and .mhd with LOCAL or single-file uncompressed data;
// other paths return at once.
#include <string>
#include <vector>

namespace colonmap::io {

// Throws colonmap::InputError (naming `what` and `path`) when the voxel data is cut short.
// Returns the axes (1-based, among the first three) ElementSpacing gives a negative spacing (ITK
// reads them as positive spacings along flipped axes, silently); empty for other paths.
std::vector<int> CheckMetaImageFile(const std::string& path, const std::string& what);

}  // namespace colonmap::io
