#include "CLI/ModuleRunner.h"

#include "CLI/OutputFolder.h"

#include "Core/Error.h"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <new>
#include <unistd.h>

namespace colonmap::cli {
namespace {

void PrintError(const char* module, const std::string& message) {
  std::fprintf(stderr, "%s: error: %s\n", module, message.c_str());
  std::fflush(stderr);
}

void Echo(const ModuleDescription& m, const Arguments& a, std::FILE* out) {
  for (const auto* p : m.Parameters()) {
    if (p->IsReturnParameter()) continue;
    std::string joined;
    for (const auto& v : a.Raw(p->name)) joined += (joined.empty() ? "" : " ; ") + v;
    std::fprintf(out, "%s = %s\n", p->name.c_str(), joined.c_str());
  }
  std::fflush(out);
}

void WriteReturnParameters(ModuleContext& ctx) {
  if (ctx.args.returnParameterFile.empty()) return;
  const std::string temp = ctx.outputs.Stage(ctx.args.returnParameterFile, "return parameter file");
  std::ofstream file(temp);
  for (const auto* p : ctx.description.Parameters()) {
    if (!p->IsReturnParameter()) continue;
    const auto it = ctx.returnValues.find(p->name);
    file << p->name << " = " << (it == ctx.returnValues.end() ? std::string() : it->second) << "\n";
  }
  if (!file.good()) throw InputError("return parameter file", ctx.args.returnParameterFile, "cannot be written");
}

}  // namespace

void ModuleContext::SetReturn(const std::string& name, const std::string& value) {
  const ParameterDescription* p = description.Find(name);
  if (!p || !p->IsReturnParameter()) throw std::logic_error("'" + name + "' is not a return parameter");
  returnValues[name] = value;
}

int RunModule(const char* moduleName, const char* xml, int argc, char** argv, ModuleBody body) {
  if (argc >= 2 && std::strcmp(argv[1], "--xml") == 0) {
    std::fwrite(xml, 1, std::strlen(xml), stdout);
    std::fflush(stdout);
    return 0;
  }
  try {
    const ModuleDescription description = ParseModuleDescription(xml);
    Arguments args;
    try {
      args = ParseCommandLine(description, moduleName, argc, argv);
    } catch (const HelpShown&) {
      std::fflush(stdout);
      return 0;
    }
    ModuleProcessInformation* info = ProcessInformationFromAddress(args.processInformationAddress.c_str());
    const Progress::Style style = info ? Progress::Style::Silent
                                  : ::isatty(::fileno(stdout)) ? Progress::Style::Terminal
                                                               : Progress::Style::SlicerTags;
    if (args.echo) Echo(description, args, stdout);
    // Before any work: "." (Slicer's unset folder), "/", someone else's folder (issue 23). Nested
    // runs are not checked: their folders are the pipeline's own, made by it.
    CheckOutputFolders(description, args);
    Progress progress(moduleName, style, info, stdout);
    OutputTransaction outputs;
    ModuleContext ctx{moduleName, description, args, progress, outputs, {}};
    try {
      body(ctx);
      WriteReturnParameters(ctx);
      if (progress.AbortRequested()) throw Cancelled();
      outputs.Commit();
      progress.Finish();
      return 0;
    } catch (const Cancelled&) {
      outputs.Rollback();
      progress.Note(std::string(moduleName) + ": cancelled, no output written");
      return 0;
    } catch (const Error& e) {
      throw Error(outputs.UserNames(e.what()));  // the user's output names, not our temporaries
    }
  } catch (const Error& e) {
    PrintError(moduleName, e.what());
    return 1;
  } catch (const std::bad_alloc&) {
    PrintError(moduleName, "out of memory");
    return 1;
  } catch (const std::exception& e) {
    PrintError(moduleName, std::string("internal error: ") + e.what());
    return 2;
  } catch (...) {
    PrintError(moduleName, "internal error (unknown exception)");
    return 2;
  }
}

std::map<std::string, std::string> RunNestedModule(ModuleContext& parent, const char* moduleName,
                                                   const char* xml, ModuleBody body,
                                                   const std::vector<std::string>& arguments) {
  return RunNestedModule(static_cast<ProgressParent&>(parent.progress), moduleName, xml, body, arguments, parent.shelf);
}

std::map<std::string, std::string> RunNestedModule(ProgressParent& parent, const char* moduleName,
                                                   const char* xml, ModuleBody body,
                                                   const std::vector<std::string>& arguments, VolumeShelf* shelf) {
  std::vector<std::string> words{moduleName};
  words.insert(words.end(), arguments.begin(), arguments.end());
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  try {
    const ModuleDescription description = ParseModuleDescription(xml);
    const Arguments args = ParseCommandLine(description, moduleName, static_cast<int>(words.size()), argv.data());
    Progress progress(moduleName, parent);
    OutputTransaction outputs;
    ModuleContext ctx{moduleName, description, args, progress, outputs, {}, shelf};
    try {
      body(ctx);
      outputs.Commit();
    } catch (const Error& e) {
      throw Error(outputs.UserNames(e.what()));  // the stage's output names, not its temporaries
    }
    progress.Finish();
    return ctx.returnValues;
  } catch (const Cancelled&) {
    throw;
  } catch (const HelpShown&) {
    throw std::logic_error(std::string(moduleName) + ": nested run asked for help");
  } catch (const Error& e) {
    throw Error(std::string(moduleName) + ": " + e.what());
  }
}

}  // namespace colonmap::cli
