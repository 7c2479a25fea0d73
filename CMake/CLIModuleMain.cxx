// The program form of every module: a one-line main over the module's shared library, as
// SlicerExecutionModel's SEMMacroBuildCLI builds it.
extern "C" int ModuleEntryPoint(int argc, char* argv[]);
int main(int argc, char* argv[]) { return ModuleEntryPoint(argc, argv); }
