// Starts as a module program does (CLI/HugePageMalloc.h) and says how often it was started and
// with which GLIBC_TUNABLES: "starts=<n> tunables=<value or (unset)>".
#include "CLI/HugePageMalloc.h"

#include <cstdio>
#include <cstdlib>
#include <string>

int main(int argc, char* argv[]) {
  const char* before = std::getenv("COLONMAP_PROBE_STARTS");
  const std::string starts = std::to_string((before ? std::atoi(before) : 0) + 1);
  setenv("COLONMAP_PROBE_STARTS", starts.c_str(), 1);
  colonmap::cli::UseHugePageMalloc(argc, argv);
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  std::printf("starts=%s tunables=%s\n", starts.c_str(), tunables ? tunables : "(unset)");
  return 0;
}
