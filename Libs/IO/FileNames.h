#pragma once
// File-name helpers shared by the readers and writers: which format a path names.
#include <cctype>
#include <string>

namespace colonmap::io {

// `s` in lower case (ASCII): extensions are matched without regard to case.
inline std::string LowerCase(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace colonmap::io
