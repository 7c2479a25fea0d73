#pragma once
// What ITK's NIfTI reader lets through (issue 24), checked on the file itself before it is read:
// a zero, NaN or infinite pixel spacing (read as 1 mm without a word), and voxel data shorter than
// the header says (a truncated .nii, or a .nii.gz whose gzip stream is cut: read as a partial
// image). Only .nii and .nii.gz (NIfTI-1 and NIfTI-2 single files); other paths return at once.
#include <string>
#include <vector>

namespace colonmap::io {

// Throws colonmap::InputError (naming `what` and `path`) when the file is not usable. Returns the
// axes (1-based) whose pixdim is negative: ITK reads them as flipped axes, which the user is told.
std::vector<int> CheckNiftiFile(const std::string& path, const std::string& what);

}  // namespace colonmap::io
