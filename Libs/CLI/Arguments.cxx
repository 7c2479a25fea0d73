#include "CLI/Arguments.h"

#include "CLI/ModuleDescription.h"
#include "Core/Error.h"

#include <tclap/CmdLine.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <sstream>

namespace colonmap::cli {
namespace {

bool ToDouble(const std::string& s, double& v) {
  const std::string t = s.substr(0, s.find_last_not_of(' ') + 1);
  if (t.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtod(t.c_str(), &end);
  return errno == 0 && *end == '\0' && std::isfinite(v);
}

bool ToLong(const std::string& s, long& v) {
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  v = std::strtol(s.c_str(), &end, 10);
  return errno == 0 && *end == '\0';
}

std::string Display(const ParameterDescription& p) {
  if (!p.longflag.empty()) return "--" + p.longflag;
  if (!p.flag.empty()) return "-" + p.flag;
  return "<" + p.name + ">";
}

std::string TypeName(const ParameterDescription& p) {
  if (p.tag == "integer" || p.tag == "integer-vector") return "integer";
  if (p.tag == "float" || p.tag == "double" || p.tag == "float-vector" || p.tag == "double-vector")
    return "number";
  return p.tag;
}

// Checks one value of a parameter against its type and constraints; throws a readable Error.
void Validate(const ParameterDescription& p, const std::string& value) {
  const auto fail = [&](const std::string& why) {
    return Error("parameter " + Display(p) + " (" + p.name + "): " + why);
  };
  auto checkRange = [&](double v, const std::string& text) {
    if (p.hasMinimum && v < p.minimum)
      throw fail("value " + text + " is below the minimum " + std::to_string(p.minimum));
    if (p.hasMaximum && v > p.maximum)
      throw fail("value " + text + " is above the maximum " + std::to_string(p.maximum));
  };
  if (p.tag == "integer" || p.tag == "integer-enumeration") {
    long v = 0;
    if (!ToLong(value, v)) throw fail("'" + value + "' is not an integer");
    checkRange(static_cast<double>(v), value);
  } else if (p.tag == "float" || p.tag == "double" || p.tag == "float-enumeration" ||
             p.tag == "double-enumeration") {
    double v = 0;
    if (!ToDouble(value, v)) throw fail("'" + value + "' is not a finite number");
    checkRange(v, value);
  } else if (p.IsVector() && p.tag != "string-vector") {
    for (const auto& part : SplitCommaList(value)) {
      double v = 0;
      long l = 0;
      const bool ok = p.tag == "integer-vector" ? ToLong(part, l) : ToDouble(part, v);
      if (!ok) throw fail("'" + value + "' is not a comma-separated list of " + TypeName(p) + "s");
      checkRange(p.tag == "integer-vector" ? static_cast<double>(l) : v, part);
    }
  } else if (p.tag == "point" || p.tag == "region") {
    const auto parts = SplitCommaList(value);
    const std::size_t n = p.tag == "point" ? 3 : 6;
    double v = 0;
    bool ok = parts.size() == n;
    for (const auto& part : parts) ok = ok && ToDouble(part, v);
    if (!ok) throw fail("'" + value + "' is not " + std::to_string(n) + " comma-separated numbers");
  }
  if (p.IsEnumeration()) {
    bool found = false;
    for (const auto& e : p.elements) found = found || e == value;
    if (!found) {
      std::string list;
      for (const auto& e : p.elements) list += (list.empty() ? "" : ", ") + e;
      throw fail("'" + value + "' is not one of: " + list);
    }
  }
}

}  // namespace

std::vector<std::string> SplitCommaList(const std::string& text) {
  std::vector<std::string> parts;
  if (text.empty()) return parts;
  std::stringstream ss(text);
  std::string item;
  while (std::getline(ss, item, ',')) {
    const auto a = item.find_first_not_of(' ');
    const auto b = item.find_last_not_of(' ');
    parts.push_back(a == std::string::npos ? std::string() : item.substr(a, b - a + 1));
  }
  if (text.back() == ',') parts.emplace_back();
  return parts;
}

void Arguments::Set(const std::string& name, std::vector<std::string> values, bool given) {
  entries_[name] = Entry{std::move(values), given};
}

const Arguments::Entry& Arguments::Lookup(const std::string& name) const {
  const auto it = entries_.find(name);
  if (it == entries_.end()) throw std::logic_error("no parameter named '" + name + "' in the XML");
  return it->second;
}

bool Arguments::Has(const std::string& name) const {
  const Entry& e = Lookup(name);
  return !e.values.empty() && !(e.values.size() == 1 && e.values[0].empty());
}
bool Arguments::Given(const std::string& name) const { return Lookup(name).given; }
const std::vector<std::string>& Arguments::Raw(const std::string& name) const {
  return Lookup(name).values;
}
std::string Arguments::GetString(const std::string& name) const {
  const Entry& e = Lookup(name);
  return e.values.empty() ? std::string() : e.values.front();
}
long Arguments::GetInt(const std::string& name) const { return std::strtol(GetString(name).c_str(), nullptr, 10); }
double Arguments::GetDouble(const std::string& name) const { return std::strtod(GetString(name).c_str(), nullptr); }
bool Arguments::GetBool(const std::string& name) const { return GetString(name) == "true"; }

std::vector<double> Arguments::GetDoubleVector(const std::string& name) const {
  std::vector<double> v;
  for (const auto& s : SplitCommaList(GetString(name))) v.push_back(std::strtod(s.c_str(), nullptr));
  return v;
}
std::vector<long> Arguments::GetIntVector(const std::string& name) const {
  std::vector<long> v;
  for (const auto& s : SplitCommaList(GetString(name))) v.push_back(std::strtol(s.c_str(), nullptr, 10));
  return v;
}
std::vector<std::string> Arguments::GetStringVector(const std::string& name) const {
  return SplitCommaList(GetString(name));
}
std::vector<Eigen::Vector3d> Arguments::GetPoints(const std::string& name) const {
  std::vector<Eigen::Vector3d> points;
  const auto ras = rasPoints_.find(name);
  const bool isRas = ras != rasPoints_.end() && ras->second;
  for (const auto& value : Lookup(name).values) {
    const auto c = SplitCommaList(value);
    if (c.size() != 3) continue;
    Eigen::Vector3d p(std::strtod(c[0].c_str(), nullptr), std::strtod(c[1].c_str(), nullptr),
                      std::strtod(c[2].c_str(), nullptr));
    if (isRas) p.head<2>() *= -1.0;
    points.push_back(p);
  }
  return points;
}

Arguments ParseCommandLine(const ModuleDescription& module, const std::string& moduleName,
                           int argc, char** argv) {
  using StringArg = TCLAP::ValueArg<std::string>;
  TCLAP::CmdLine cmd(module.title + ": " + module.description, ' ',
                     module.version.empty() ? "0" : module.version, true);
  cmd.setExceptionHandling(false);

  // TCLAP needs each Arg alive until parse(); keep them here, keyed by parameter name.
  std::vector<std::unique_ptr<TCLAP::Arg>> owned;
  std::map<std::string, TCLAP::Arg*> byName;
  std::vector<const ParameterDescription*> indexed;

  for (const ParameterDescription* p : module.Parameters()) {
    if (p->IsReturnParameter()) continue;
    if (p->index >= 0) {
      indexed.push_back(p);
      continue;
    }
    if (p->flag == "h" || p->flag == "v" || p->longflag == "help" || p->longflag == "version")
      throw std::logic_error("parameter '" + p->name + "' uses a flag reserved for --help/--version");
    const std::string doc = p->label + (p->description.empty() ? "" : ": " + p->description) +
                            (p->hasDefault && !p->defaultValue.empty() ? " (default " + p->defaultValue + ")" : "");
    if (p->tag == "boolean") {
      if (p->defaultValue == "true")
        throw std::logic_error("boolean '" + p->name + "' defaults to true: Slicer cannot switch it off");
      owned.push_back(std::make_unique<TCLAP::SwitchArg>(p->flag, p->longflag, doc, false));
    } else if (p->multiple) {
      owned.push_back(std::make_unique<TCLAP::MultiArg<std::string>>(p->flag, p->longflag, doc, false, p->tag));
    } else {
      owned.push_back(std::make_unique<StringArg>(p->flag, p->longflag, doc, false, p->defaultValue, p->tag));
    }
    byName[p->name] = owned.back().get();
  }
  std::sort(indexed.begin(), indexed.end(), [](auto* a, auto* b) { return a->index < b->index; });
  // TCLAP lists flagged arguments in reverse order of addition: add in reverse to keep XML order
  // in --help. Unlabeled (index) arguments take positions in order of addition.
  for (auto it = owned.rbegin(); it != owned.rend(); ++it) cmd.add(it->get());
  for (const ParameterDescription* p : indexed) {
    owned.push_back(std::make_unique<TCLAP::UnlabeledValueArg<std::string>>(
        p->name, p->label + ": " + p->description, true, "", p->tag));
    byName[p->name] = owned.back().get();
    cmd.add(owned.back().get());
  }

  TCLAP::SwitchArg echo("", "echo", "Print the parsed parameter values, then run", false);
  TCLAP::SwitchArg xml("", "xml", "Print the module's XML description and exit", false);
  StringArg returnFile("", "returnparameterfile", "File to write return parameters to", false, "", "file");
  StringArg processInfo("", "processinformationaddress", "Address of a Slicer ModuleProcessInformation", false, "", "address");
  cmd.add(echo);
  cmd.add(xml);
  cmd.add(returnFile);
  cmd.add(processInfo);

  std::vector<std::string> args(argv, argv + argc);
  if (!args.empty()) args[0] = moduleName;  // in-process argv[0] is "slicer:0x..": never use it
  try {
    cmd.parse(args);
  } catch (TCLAP::ExitException&) {
    throw HelpShown{};
  } catch (TCLAP::ArgException& e) {
    std::string id = e.argId();
    throw Error("command line: " + e.error() + (id.empty() || id == " " ? "" : " (" + id + ")") +
                "; run " + moduleName + " --help for usage");
  }

  Arguments result;
  result.echo = echo.getValue();
  result.returnParameterFile = returnFile.getValue();
  result.processInformationAddress = processInfo.getValue();
  for (const ParameterDescription* p : module.Parameters()) {
    if (p->IsReturnParameter()) {
      result.Set(p->name, {}, false);
      continue;
    }
    TCLAP::Arg* arg = byName.at(p->name);
    std::vector<std::string> values;
    if (p->tag == "boolean") {
      values.push_back(static_cast<TCLAP::SwitchArg*>(arg)->getValue() ? "true" : "false");
    } else if (p->multiple && p->index < 0) {
      values = static_cast<TCLAP::MultiArg<std::string>*>(arg)->getValue();
    } else {
      values.push_back(static_cast<StringArg*>(arg)->getValue());
    }
    for (const auto& v : values)
      if (!(v.empty() && !arg->isSet())) Validate(*p, v);
    result.Set(p->name, std::move(values), arg->isSet());
    result.rasPoints_[p->name] = p->coordinateSystem == "ras";
  }
  return result;
}

}  // namespace colonmap::cli
