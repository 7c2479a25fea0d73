#include "CLI/HugePageMalloc.h"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

#include <unistd.h>

namespace colonmap::cli {

#if defined(__linux__) && defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 35))
#define COLONMAP_GLIBC_HAS_HUGETLB_TUNABLE 1
#endif

bool HugePageMallocAvailable() {
#ifdef COLONMAP_GLIBC_HAS_HUGETLB_TUNABLE
  std::ifstream f("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(f, line) && line.find("[never]") == std::string::npos;
#else
  return false;
#endif
}

void UseHugePageMalloc(int argc, char* argv[]) {
#ifdef COLONMAP_GLIBC_HAS_HUGETLB_TUNABLE
  if (argc > 1 && std::strcmp(argv[1], "--xml") == 0) return;
  if (std::getenv("COLONMAP_NO_HUGE_PAGES")) return;
  const char* current = std::getenv("GLIBC_TUNABLES");
  if (current && std::strstr(current, "glibc.malloc.hugetlb")) return;  // also what stops a second restart
  if (!HugePageMallocAvailable()) return;
  const std::string before = current ? current : "";
  const std::string value = before.empty() ? "glibc.malloc.hugetlb=1" : before + ":glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", value.c_str(), 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Not restarted: go on as before, with the environment as it was.
  if (current) setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else unsetenv("GLIBC_TUNABLES");
#else
  (void)argc;
  (void)argv;
#endif
}

}  // namespace colonmap::cli
