#include "CLI/ModuleDescription.h"

#include "Core/Error.h"

#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <set>

namespace colonmap::cli {
namespace {

const std::set<std::string>& ParameterTags() {
  static const std::set<std::string> tags = {
      "integer", "float", "double", "boolean", "string", "integer-vector", "float-vector",
      "double-vector", "string-vector", "integer-enumeration", "float-enumeration",
      "double-enumeration", "string-enumeration", "file", "directory", "image", "geometry",
      "point", "pointfile", "region", "table", "transform", "measurement"};
  return tags;
}

std::string Trim(const char* text) {
  if (!text) return {};
  std::string s(text);
  const auto first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = s.find_last_not_of(" \t\r\n");
  return s.substr(first, last - first + 1);
}

std::string StripDashes(std::string s) {
  s.erase(0, s.find_first_not_of('-'));
  return s;
}

// The whole text is a finite number ("nan" or "1e999" as a minimum would switch the check off).
bool ParseNumber(const std::string& text, double& value) {
  char* end = nullptr;
  value = std::strtod(text.c_str(), &end);
  return !text.empty() && end && *end == '\0' && std::isfinite(value);
}

// An <index>: a non-negative integer, the whole text (atoi took "-5" as "no index", "x" as 0).
int ParseIndex(const std::string& text, const std::string& tag) {
  char* end = nullptr;
  errno = 0;
  const long v = std::strtol(text.c_str(), &end, 10);
  if (text.empty() || !end || *end != '\0' || errno != 0 || v < 0 || v > 100000)
    throw Error("module description: a <" + tag + "> parameter has <index> '" + text + "', not a non-negative integer");
  return static_cast<int>(v);
}

ParameterDescription ParseParameter(vtkXMLDataElement* e) {
  ParameterDescription p;
  p.tag = e->GetName();
  if (const char* m = e->GetAttribute("multiple")) p.multiple = std::string(m) == "true";
  if (const char* h = e->GetAttribute("hidden")) p.hidden = std::string(h) == "true";
  if (const char* c = e->GetAttribute("coordinateSystem")) p.coordinateSystem = c;
  if (const char* x = e->GetAttribute("fileExtensions")) p.fileExtensions = x;
  for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* c = e->GetNestedElement(i);
    const std::string n = c->GetName();
    const std::string text = Trim(c->GetCharacterData());
    if (n == "name") p.name = text;
    else if (n == "label") p.label = text;
    else if (n == "description") p.description = text;
    else if (n == "flag") p.flag = StripDashes(text);
    else if (n == "longflag") p.longflag = StripDashes(text);
    else if (n == "index") p.index = ParseIndex(text, p.tag);
    else if (n == "channel") p.channel = text;
    else if (n == "default") { p.defaultValue = text; p.hasDefault = true; }
    else if (n == "element") p.elements.push_back(text);
    else if (n == "constraints") {
      for (int k = 0; k < c->GetNumberOfNestedElements(); ++k) {
        vtkXMLDataElement* b = c->GetNestedElement(k);
        const std::string bn = b->GetName();
        if (bn != "minimum" && bn != "maximum") continue;
        double v = 0.0;
        const std::string number = Trim(b->GetCharacterData());
        if (!ParseNumber(number, v))
          throw Error("module description: a <" + p.tag + "> parameter has <" + bn + "> '" + number + "', not a finite number");
        if (bn == "minimum") { p.minimum = v; p.hasMinimum = true; }
        if (bn == "maximum") { p.maximum = v; p.hasMaximum = true; }
      }
    }
  }
  if (p.name.empty()) throw Error("module description: a <" + p.tag + "> parameter has no <name>");
  if (p.index >= 0 && (!p.flag.empty() || !p.longflag.empty()))
    throw Error("module description: parameter '" + p.name + "' has both an index and a flag");
  if (p.IsEnumeration() && p.elements.empty())
    throw Error("module description: enumeration '" + p.name + "' has no <element>");
  return p;
}

}  // namespace

bool ParameterDescription::IsReturnParameter() const {
  return channel == "output" && index < 0 && flag.empty() && longflag.empty();
}
bool ParameterDescription::IsVector() const {
  return tag.size() > 7 && tag.compare(tag.size() - 7, 7, "-vector") == 0;
}
bool ParameterDescription::IsEnumeration() const {
  return tag.find("-enumeration") != std::string::npos;
}
bool ParameterDescription::IsNumeric() const {
  return tag == "integer" || tag == "float" || tag == "double";
}

std::vector<const ParameterDescription*> ModuleDescription::Parameters() const {
  std::vector<const ParameterDescription*> all;
  for (const auto& g : groups)
    for (const auto& p : g.parameters) all.push_back(&p);
  return all;
}

const ParameterDescription* ModuleDescription::Find(const std::string& name) const {
  for (const auto* p : Parameters())
    if (p->name == name) return p;
  return nullptr;
}

bool ModuleDescription::HasReturnParameters() const {
  const auto all = Parameters();
  return std::any_of(all.begin(), all.end(), [](const auto* p) { return p->IsReturnParameter(); });
}

ModuleDescription ParseModuleDescription(const std::string& xml) {
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromString(xml.c_str()));
  if (!root || std::string(root->GetName()) != "executable")
    throw Error("module description: not an <executable> XML document");
  ModuleDescription m;
  std::set<std::string> names;
  std::set<int> indices;
  for (int i = 0; i < root->GetNumberOfNestedElements(); ++i) {
    vtkXMLDataElement* e = root->GetNestedElement(i);
    const std::string n = e->GetName();
    const std::string text = Trim(e->GetCharacterData());
    if (n == "title") m.title = text;
    else if (n == "category") m.category = text;
    else if (n == "description") m.description = text;
    else if (n == "version") m.version = text;
    else if (n == "documentation-url") m.documentationUrl = text;
    else if (n == "license") m.license = text;
    else if (n == "contributor") m.contributor = text;
    else if (n == "acknowledgements") m.acknowledgements = text;
    else if (n == "parameters") {
      ParameterGroup g;
      if (const char* a = e->GetAttribute("advanced")) g.advanced = std::string(a) == "true";
      for (int k = 0; k < e->GetNumberOfNestedElements(); ++k) {
        vtkXMLDataElement* c = e->GetNestedElement(k);
        const std::string cn = c->GetName();
        if (cn == "label") g.label = Trim(c->GetCharacterData());
        else if (cn == "description") g.description = Trim(c->GetCharacterData());
        else if (ParameterTags().count(cn)) {
          ParameterDescription p = ParseParameter(c);
          if (!names.insert(p.name).second)
            throw Error("module description: parameter name '" + p.name + "' used twice");
          if (p.index >= 0 && !indices.insert(p.index).second)
            throw Error("module description: index " + std::to_string(p.index) + " used twice");
          g.parameters.push_back(std::move(p));
        } else {
          throw Error("module description: unknown parameter tag <" + cn + ">");
        }
      }
      m.groups.push_back(std::move(g));
    }
  }
  return m;
}

}  // namespace colonmap::cli
