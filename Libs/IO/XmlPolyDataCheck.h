#pragma once
// Checks an XML PolyData file (.vtp) for what VTK 9.1's reader trusts and should not (found by
// fuzzing, issue 24, docs/fuzzing.md), before that reader is given the file: malformed structure,
// counts and compression headers that would make it allocate without bound, read through a null
// array or write past an array's end. The list is in XmlPolyDataCheck.cxx.
#include <string>

namespace colonmap::io {

// The problem in a few words, or "" when there is none (or when VTK itself will refuse the file:
// it is not XML).
std::string CheckXmlPolyData(const std::string& path);

}  // namespace colonmap::io
