#include "SlicerCommandLine.h"

#include <algorithm>

namespace colonmap::testing {

std::vector<std::string> SlicerArguments(const cli::ModuleDescription& module,
                                         const std::map<std::string, std::string>& values) {
  std::vector<std::string> args;
  std::vector<const cli::ParameterDescription*> indexed;
  for (const auto* p : module.Parameters()) {
    if (p->IsReturnParameter()) continue;
    if (p->index >= 0) {
      indexed.push_back(p);
      continue;
    }
    const auto it = values.find(p->name);
    const std::string flag = p->longflag.empty() ? "-" + p->flag : "--" + p->longflag;
    const bool always = p->IsNumeric() || p->IsEnumeration();
    std::string value = it != values.end() ? it->second : (always ? p->defaultValue : std::string());
    if (p->tag == "boolean") {
      if (value == "true") args.push_back(flag);
      continue;
    }
    if (value.empty()) continue;
    args.push_back(flag);
    args.push_back(value);
  }
  std::sort(indexed.begin(), indexed.end(), [](auto* a, auto* b) { return a->index < b->index; });
  for (const auto* p : indexed) args.push_back(values.at(p->name));
  return args;
}

}  // namespace colonmap::testing
