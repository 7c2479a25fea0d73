// The program form of every module: a one-line main over the module's shared library, as
// SlicerExecutionModel's SEMMacroBuildCLI builds it; first the restart with huge-page malloc
// (CLI/HugePageMalloc.h), which only a program of its own may do.
#include "CLI/HugePageMalloc.h"

extern "C" int ModuleEntryPoint(int argc, char* argv[]);
int main(int argc, char* argv[]) {
  colonmap::cli::UseHugePageMalloc(argc, argv);
  return ModuleEntryPoint(argc, argv);
}
