#pragma once
// The CLI tests' module description (AllTypes.xml: every parameter type), as text.
#include <fstream>
#include <sstream>
#include <string>

inline std::string AllTypesXml() {
  std::ifstream in(COLONMAP_TEST_XML);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
