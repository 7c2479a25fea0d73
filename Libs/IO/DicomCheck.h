#pragma once
// What GDCM cannot be trusted with (issue 24), checked on the files of a DICOM folder before GDCM
// reads any of them: a slice file cut short (GDCM aborts the process on an assertion when the cut
// falls before the pixel data, and native pixel data cut short is read as a partial image), and a
// slice whose rows or columns differ from the others of its series (GDCM puts it in a series of
// its own, so that it is dropped without a word). The check walks each file's data elements with
// their lengths, nothing more: decoding stays with GDCM.
#include <string>

namespace colonmap::io {

// Throws colonmap::InputError naming `what` and `folder` (and the slice file) when a DICOM file in
// `folder` (Part 10, or an old-style data set without preamble) is cut short or holds no pixel
// data, or when a series mixes slice sizes. Other files are left to GDCM. Returns the number of
// DICOM files seen.
int CheckDicomFolder(const std::string& folder, const std::string& what);

}  // namespace colonmap::io
