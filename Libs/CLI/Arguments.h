#pragma once
// Parsed, validated parameter values of one module run, looked up by the XML <name>.
// Values are stored as the strings given (or the XML default); typed getters convert them.
// Validation (types, min/max, enumerations, point arity) happens once in ParseCommandLine.
#include <Eigen/Core>
#include <map>
#include <string>
#include <vector>

namespace colonmap::cli {

struct ModuleDescription;

class Arguments {
 public:
  // Set by the parser.
  void Set(const std::string& name, std::vector<std::string> values, bool given);

  bool Has(const std::string& name) const;    // given on the command line, or non-empty default
  bool Given(const std::string& name) const;  // given on the command line
  std::string GetString(const std::string& name) const;
  long GetInt(const std::string& name) const;
  double GetDouble(const std::string& name) const;
  bool GetBool(const std::string& name) const;
  std::vector<double> GetDoubleVector(const std::string& name) const;
  std::vector<long> GetIntVector(const std::string& name) const;
  std::vector<std::string> GetStringVector(const std::string& name) const;
  // point parameters (possibly multiple) in LPS mm, whatever coordinateSystem the XML declares.
  std::vector<Eigen::Vector3d> GetPoints(const std::string& name) const;

  // Raw values of a parameter (all occurrences for multiple ones).
  const std::vector<std::string>& Raw(const std::string& name) const;

  // Options of the run that are not module parameters.
  bool echo = false;
  std::string returnParameterFile;
  std::string processInformationAddress;

 private:
  struct Entry {
    std::vector<std::string> values;
    bool given = false;
  };
  const Entry& Lookup(const std::string& name) const;
  std::map<std::string, Entry> entries_;
  std::map<std::string, bool> rasPoints_;
  friend Arguments ParseCommandLine(const ModuleDescription&, const std::string&, int, char**);
};

// Parses argv with TCLAP, driven by the module description. Throws colonmap::Error with one
// readable line for bad command lines. Throws HelpShown after printing --help or --version.
Arguments ParseCommandLine(const ModuleDescription& module, const std::string& moduleName,
                           int argc, char** argv);

struct HelpShown {};

// Splits "1,2,3" into its parts (no trimming of inner text beyond spaces).
std::vector<std::string> SplitCommaList(const std::string& text);

}  // namespace colonmap::cli
