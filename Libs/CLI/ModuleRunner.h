#pragma once
// Runs one module the way both of Slicer's hosts expect (DESIGN §3.1, §3.1a): --xml, --help,
// --version, --echo, TCLAP parsing from the XML, progress, return parameters, all-or-nothing
// outputs, Cancel, and one clear stderr line with a non-zero exit on failure. Module code only
// writes the body. Nothing here calls exit(), changes process state or keeps mutable statics.
#include "CLI/Arguments.h"
#include "CLI/ModuleDescription.h"
#include "CLI/OutputTransaction.h"
#include "CLI/Progress.h"

#include <functional>
#include <map>
#include <string>
#include <vector>

// What a module's shared library exports; nothing else is visible (see CMake/CLIModule.map).
#define COLONMAP_CLI_EXPORT extern "C" __attribute__((visibility("default")))

// Names a module's body: defines colonmap::modules::Run<Name>, which the generated entry point
// (CMake/EmbedXML.cmake) passes to RunModule and which pipeline modules run in-process.
#define COLONMAP_MODULE_BODY(Name, function)                                    \
  namespace colonmap::modules {                                                 \
  void Run##Name(cli::ModuleContext& ctx);                                      \
  }                                                                             \
  void colonmap::modules::Run##Name(colonmap::cli::ModuleContext& ctx) { function(ctx); }

// Declares another module's body and XML (link its <Name>Body library) for RunNestedModule.
#define COLONMAP_DECLARE_MODULE(Name)      \
  namespace colonmap::modules {            \
  void Run##Name(cli::ModuleContext& ctx); \
  extern const char Name##XML[];           \
  }

namespace colonmap {
class VolumeShelf;
}

namespace colonmap::cli {

struct ModuleContext {
  std::string moduleName;
  const ModuleDescription& description;
  const Arguments& args;
  Progress& progress;
  OutputTransaction& outputs;
  std::map<std::string, std::string> returnValues;  // written to --returnparameterfile
  // Run as a stage of a pipeline in one process: volumes handed on in memory (Core/VolumeShelf.h;
  // io::ReadImageKept), else null.
  VolumeShelf* shelf = nullptr;

  void SetReturn(const std::string& name, const std::string& value);
  // What a reader tells the user about how it read a file (io::NoteSink): "<Module>: note: ..."
  // on stdout through the progress, never stderr. Notes about our own hidden intermediates (a
  // pipeline's stage folders) are dropped: the user heard it once, about their own file.
  std::function<void(const std::string&)> ReaderNotes() {
    return [this](const std::string& text) {
      if (text.find(".colonmap-tmp-") == std::string::npos) progress.Note(moduleName + ": note: " + text);
    };
  }
};

using ModuleBody = void (*)(ModuleContext&);

// The whole of a module's ModuleEntryPoint. `xml` is the embedded description.
int RunModule(const char* moduleName, const char* xml, int argc, char** argv, ModuleBody body);

// Runs another module's body in this process as the current stage of `parent` (a pipeline
// module such as ColonSupineProne). `arguments` are its command line without argv[0], parsed
// and checked against its XML as on the command line; its progress fills the parent's current
// stage, its notes go to the parent, the parent's Abort stops it; its outputs are committed
// when it succeeds. Errors come back as colonmap::Error prefixed with the module's name.
// Returns its return parameters.
std::map<std::string, std::string> RunNestedModule(ModuleContext& parent, const char* moduleName,
                                                   const char* xml, ModuleBody body,
                                                   const std::vector<std::string>& arguments);
// The same into any progress parent (a job on its own thread: CLI/StageChain.h), with the
// pipeline's shelf of volumes (may be null).
std::map<std::string, std::string> RunNestedModule(ProgressParent& parent, const char* moduleName,
                                                   const char* xml, ModuleBody body,
                                                   const std::vector<std::string>& arguments,
                                                   VolumeShelf* shelf = nullptr);

}  // namespace colonmap::cli
