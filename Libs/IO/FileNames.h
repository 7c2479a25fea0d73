#pragma once
// Helpers shared by the readers, writers and header checks: which format a path names, what a
// header's spacing list says, a byte count for a message.
#include <cctype>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

namespace colonmap::io {

// `s` in lower case (ASCII): extensions are matched without regard to case.
inline std::string LowerCase(std::string s) {
  for (auto& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// `s` without leading and trailing blanks (spaces, tabs, a CR of a Windows line end).
inline std::string Trim(const std::string& s) {
  const std::size_t a = s.find_first_not_of(" \t\r"), b = s.find_last_not_of(" \t\r");
  return a == std::string::npos ? std::string() : s.substr(a, b - a + 1);
}

// Whether `s` ends with `tail` (case as given).
inline bool EndsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The axes (1-based, among the three of the image we read) with a negative value in a header's
// list of spacings ("0.7 -0.7 1"). A longer list (found by fuzzing: 20 values) must not make the
// user's note name an "axis 17".
inline std::vector<int> NegativeAxes(const std::string& spacings) {
  std::vector<int> axes;
  std::istringstream values(spacings);
  double v;
  for (int axis = 1; axis <= 3 && values >> v; ++axis)
    if (v < 0.0) axes.push_back(axis);
  return axes;
}

// A byte count as text: a header's sizes can promise more bytes than a long long holds (a fuzzed
// NIfTI header: 1.8e28), so no integer cast.
inline std::string ByteCount(double bytes) {
  char b[64];
  std::snprintf(b, sizeof b, "%.0f", bytes);
  return b;
}

}  // namespace colonmap::io
