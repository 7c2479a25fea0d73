#pragma once
// For tests: a new, empty folder under the system's temporary folder, named after the test
// group, the case and this process (test programs run side by side under ctest -j).
#include <filesystem>
#include <string>
#include <unistd.h>

namespace colonmap {

inline std::filesystem::path FreshTempDir(const std::string& group, const std::string& name) {
  const std::filesystem::path p =
      std::filesystem::temp_directory_path() / ("colonmap-" + group + "-" + name + "-" + std::to_string(::getpid()));
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p;
}

}  // namespace colonmap
