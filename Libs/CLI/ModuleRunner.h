#pragma once
// Runs one module the way both of Slicer's hosts expect (DESIGN §3.1, §3.1a): --xml, --help,
// --version, --echo, TCLAP parsing from the XML, progress, return parameters, all-or-nothing
// outputs, Cancel, and one clear stderr line with a non-zero exit on failure. Module code only
// writes the body. Nothing here calls exit(), changes process state or keeps mutable statics.
#include "CLI/Arguments.h"
#include "CLI/ModuleDescription.h"
#include "CLI/OutputTransaction.h"
#include "CLI/Progress.h"

#include <map>
#include <string>

// What a module's shared library exports; nothing else is visible (see CMake/CLIModule.map).
#define COLONMAP_CLI_EXPORT extern "C" __attribute__((visibility("default")))

namespace colonmap::cli {

struct ModuleContext {
  std::string moduleName;
  const ModuleDescription& description;
  const Arguments& args;
  Progress& progress;
  OutputTransaction& outputs;
  std::map<std::string, std::string> returnValues;  // written to --returnparameterfile

  void SetReturn(const std::string& name, const std::string& value);
};

using ModuleBody = void (*)(ModuleContext&);

// The whole of a module's ModuleEntryPoint. `xml` is the embedded description.
int RunModule(const char* moduleName, const char* xml, int argc, char** argv, ModuleBody body);

}  // namespace colonmap::cli
