#pragma once
// Run as a program, a module restarts itself once (execv of /proc/self/exe, same arguments, before
// anything is read or printed) with glibc's malloc told to back its blocks with transparent huge
// pages (GLIBC_TUNABLES glibc.malloc.hugetlb=1, glibc >= 2.35). Our stages allocate and free
// CT-sized buffers (hundreds of MB) many times; with 4 KB pages the kernel faults and zeroes each
// page of every new buffer: measured on the clinical phantom pair, a third of the CPU time was
// system time, and the whole pipeline ran in 45 s instead of 71 s with the restart
// (docs/performance.md). The tunable can only be set before the process starts, hence the restart.
//
// Does nothing when GLIBC_TUNABLES already names glibc.malloc.hugetlb (the restarted process, or a
// user's own choice), when COLONMAP_NO_HUGE_PAGES is set, when the kernel's transparent huge pages
// are off, for `--xml` (Slicer asks every module at start-up), or where the restart fails (the
// program then goes on as it is). Never called in a host's own process (the library form):
// only CMake/CLIModuleMain.cxx calls it.
namespace colonmap::cli {

void UseHugePageMalloc(int argc, char* argv[]);

// Whether the restart can help here: glibc >= 2.35 on Linux and transparent huge pages not off.
bool HugePageMallocAvailable();

}  // namespace colonmap::cli
