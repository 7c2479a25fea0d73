#pragma once
// Shared by the fuzz targets: a per-process temporary folder, the input written to a file there
// (our readers take paths), and the contract check that turns silently accepted bad input into a
// finding (abort()).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace fuzz {

inline const std::filesystem::path& TempDir() {
  static const std::filesystem::path dir = [] {
    std::filesystem::path d = std::filesystem::temp_directory_path() / ("colonmap-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    std::atexit([] {
      std::error_code ec;
      std::filesystem::remove_all(std::filesystem::temp_directory_path() / ("colonmap-fuzz-" + std::to_string(::getpid())), ec);
    });
    return d;
  }();
  return dir;
}

// Writes the bytes to <temp>/input<extension> and returns the path.
inline std::string WriteInput(const uint8_t* data, size_t size, const std::string& extension) {
  const std::string path = (TempDir() / ("input" + extension)).string();
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  return path;
}

// The reader returned normally with a result that breaks its contract: a finding.
[[noreturn]] inline void Violation(const char* what) {
  std::fprintf(stderr, "CONTRACT VIOLATION: %s\n", what);
  std::abort();
}

}  // namespace fuzz
