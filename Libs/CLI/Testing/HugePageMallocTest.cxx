// The restart with huge-page malloc (CLI/HugePageMalloc.h), through a probe program that starts
// as the module programs do.
#include "CLI/HugePageMalloc.h"

#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <string>

namespace {

std::string RunProbe(const std::string& environment, const std::string& arguments = "x") {
  const std::string command = "env -u GLIBC_TUNABLES -u COLONMAP_NO_HUGE_PAGES -u COLONMAP_PROBE_STARTS " + environment +
                              " '" COLONMAP_HUGE_PAGE_PROBE "' " + arguments;
  std::string out;
  if (FILE* p = popen(command.c_str(), "r")) {
    std::array<char, 512> buffer{};
    while (fgets(buffer.data(), buffer.size(), p)) out += buffer.data();
    pclose(p);
  }
  return out;
}

}  // namespace

TEST(HugePageMalloc, RestartsOnceWithTheTunableAndKeepsTheUsersOwn) {
  if (!colonmap::cli::HugePageMallocAvailable()) {
    EXPECT_EQ(RunProbe(""), "starts=1 tunables=(unset)\n");
    GTEST_SKIP() << "no transparent huge pages or glibc < 2.35 here: the program must not restart";
  }
  EXPECT_EQ(RunProbe(""), "starts=2 tunables=glibc.malloc.hugetlb=1\n");
  // A user's tunables are kept, ours appended.
  EXPECT_EQ(RunProbe("GLIBC_TUNABLES=glibc.malloc.tcache_count=0"),
            "starts=2 tunables=glibc.malloc.tcache_count=0:glibc.malloc.hugetlb=1\n");
}

TEST(HugePageMalloc, DoesNotRestartWhenToldOrChosenOrForXml) {
  EXPECT_EQ(RunProbe("COLONMAP_NO_HUGE_PAGES=1"), "starts=1 tunables=(unset)\n");
  EXPECT_EQ(RunProbe("GLIBC_TUNABLES=glibc.malloc.hugetlb=0"), "starts=1 tunables=glibc.malloc.hugetlb=0\n");
  EXPECT_EQ(RunProbe("", "--xml"), "starts=1 tunables=(unset)\n");
}
