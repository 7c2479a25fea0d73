#pragma once
// File-name helpers shared by the readers and writers: which format a path names.
#include <cctype>
#include <sstream>
#include <string>
#include <vector>

namespace colonmap::io {

// `s` in lower case (ASCII): extensions are matched without regard to case.
inline std::string LowerCase(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Whether `s` ends with `tail` (case as given).
inline bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The axes (1-based) with a negative value in a header's list of spacings ("0.7 -0.7 1").
inline std::vector<int> NegativeAxes(const std::string& spacings) {
  std::vector<int> axes;
  std::istringstream values(spacings);
  double v;
  for (int axis = 1; values >> v; ++axis)
    if (v < 0.0) axes.push_back(axis);
  return axes;
}

}  // namespace colonmap::io
