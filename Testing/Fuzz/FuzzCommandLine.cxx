// The command line and the module description. First byte 'X': the rest is a module XML for
// ParseModuleDescription. Otherwise the first byte chooses one of our modules' real XML
// descriptions and the rest, split at NUL bytes, is argv[1..] for ParseCommandLine.
// Contract when a parse returns: parameter names non-empty and unique, indices unique, minimum
// and maximum finite; parsed numbers, vectors and points finite, enumerations one of their
// elements.
#include "FuzzCommon.h"
#include "CLI/Arguments.h"
#include "CLI/ModuleDescription.h"
#include "Core/Error.h"

#include <vtkObject.h>
#include <vtkOutputWindow.h>

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <vector>

namespace {

const std::vector<colonmap::cli::ModuleDescription>& Modules() {
  static const std::vector<colonmap::cli::ModuleDescription> modules = [] {
    std::vector<colonmap::cli::ModuleDescription> m;
    std::istringstream names(COLONMAP_MODULES);
    std::string name;
    while (names >> name) {
      std::ifstream in(std::string(COLONMAP_SOURCE_DIR) + "/Modules/CLI/" + name + "/" + name + ".xml");
      std::stringstream ss;
      ss << in.rdbuf();
      m.push_back(colonmap::cli::ParseModuleDescription(ss.str()));
    }
    if (m.empty()) fuzz::Violation("no module XML found");
    return m;
  }();
  return modules;
}

bool Finite(const std::string& s) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  return end != s.c_str() && std::isfinite(v);
}

void CheckDescription(const colonmap::cli::ModuleDescription& m) {
  std::set<std::string> names;
  std::set<int> indices;
  for (const auto* p : m.Parameters()) {
    if (p->name.empty()) fuzz::Violation("parameter without a name");
    if (!names.insert(p->name).second) fuzz::Violation("parameter name used twice");
    if (p->index >= 0 && !indices.insert(p->index).second) fuzz::Violation("index used twice");
    if (p->index < -1) fuzz::Violation("negative index accepted");
    if ((p->hasMinimum && !std::isfinite(p->minimum)) || (p->hasMaximum && !std::isfinite(p->maximum)))
      fuzz::Violation("non-finite minimum or maximum accepted");
    if (p->IsEnumeration() && p->elements.empty()) fuzz::Violation("enumeration without elements");
  }
}

void CheckArguments(const colonmap::cli::ModuleDescription& m, const colonmap::cli::Arguments& a) {
  for (const auto* p : m.Parameters()) {
    if (p->IsReturnParameter() || !a.Given(p->name)) continue;
    for (const std::string& v : a.Raw(p->name)) {
      if (p->IsNumeric() && !Finite(v)) fuzz::Violation("non-finite number accepted");
      if (p->IsVector() && p->tag != "string-vector")
        for (const auto& part : colonmap::cli::SplitCommaList(v))
          if (!Finite(part)) fuzz::Violation("non-finite vector element accepted");
      if (p->IsEnumeration()) {
        bool found = false;
        for (const auto& e : p->elements) found = found || e == v;
        if (!found) fuzz::Violation("enumeration value not among its elements");
      }
    }
    if (p->tag == "point") {
      const auto points = a.GetPoints(p->name);
      if (points.size() != a.Raw(p->name).size()) fuzz::Violation("a point was dropped");
      for (const auto& q : points)
        if (!q.allFinite()) fuzz::Violation("non-finite point accepted");
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  vtkObject::GlobalWarningDisplayOff();
  // --help and --version print to stdout: keep the fuzzer's output readable.
  if (!std::freopen("/dev/null", "w", stdout)) return 0;
  Modules();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t kind = data[0];
  const std::string rest(reinterpret_cast<const char*>(data) + 1, size - 1);
  if (kind == 'X') {
    try {
      CheckDescription(colonmap::cli::ParseModuleDescription(rest));
    } catch (const colonmap::Error&) {
    }
    return 0;
  }
  const auto& modules = Modules();
  const auto& module = modules[kind % modules.size()];
  std::vector<std::string> words{"ColonFuzz"};
  std::string word;
  for (char c : rest) {
    if (c == '\0') {
      words.push_back(word);
      word.clear();
    } else {
      word += c;
    }
  }
  if (!rest.empty()) words.push_back(word);
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  try {
    CheckArguments(module, colonmap::cli::ParseCommandLine(module, "ColonFuzz", static_cast<int>(words.size()), argv.data()));
  } catch (const colonmap::Error&) {
  } catch (const colonmap::cli::HelpShown&) {
  }
  return 0;
}
