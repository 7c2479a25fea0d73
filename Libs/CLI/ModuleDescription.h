#pragma once
// The parsed form of a Slicer CLI module's XML description (SlicerExecutionModel grammar).
// The XML is the single source of truth for a module's parameters: the command-line parser,
// --help and --echo are all driven from this structure.
#include <string>
#include <vector>

namespace colonmap::cli {

struct ParameterDescription {
  std::string tag;          // integer, double, boolean, string-enumeration, image, point, ...
  std::string name;         // C identifier used by module code to look the value up
  std::string label;
  std::string description;
  std::string flag;         // one character, without the dash (may be empty)
  std::string longflag;     // without the dashes (may be empty)
  int index = -1;           // position among the index arguments, -1 when flagged
  std::string channel;      // input | output (files, images, ...)
  std::string defaultValue;
  bool hasDefault = false;
  bool multiple = false;    // attribute multiple="true" (points, files)
  bool hasMinimum = false, hasMaximum = false;
  double minimum = 0.0, maximum = 0.0;
  std::vector<std::string> elements;  // enumeration values
  std::string coordinateSystem;       // point/region/pointfile: lps | ras (empty: unspecified)
  std::string fileExtensions;         // as written in the XML, e.g. ".mrk.json"
  bool hidden = false;

  // A return parameter: an output with neither flag nor index (written to --returnparameterfile).
  bool IsReturnParameter() const;
  bool IsVector() const;        // integer-vector, float-vector, double-vector, string-vector
  bool IsEnumeration() const;
  bool IsNumeric() const;       // integer, float, double (scalars)
};

struct ParameterGroup {
  std::string label;
  std::string description;
  bool advanced = false;
  std::vector<ParameterDescription> parameters;
};

struct ModuleDescription {
  std::string title, category, description, version, documentationUrl, license, contributor,
      acknowledgements;
  std::vector<ParameterGroup> groups;

  // All parameters in XML order.
  std::vector<const ParameterDescription*> Parameters() const;
  // nullptr when there is none of that name.
  const ParameterDescription* Find(const std::string& name) const;
  bool HasReturnParameters() const;
};

// Parses the XML text. Throws colonmap::Error with a clear message on malformed descriptions
// (unknown tag, missing name, flag and index together, duplicated names or indices).
ModuleDescription ParseModuleDescription(const std::string& xml);

}  // namespace colonmap::cli
