#pragma once
// Builds a module's command line the way 3D Slicer does (DESIGN §3.1a), from the module's XML
// and a table of values keyed by parameter name: flags in XML order, numbers and enumerations
// always passed (XML default when the table has no value), booleans only when true, empty
// strings, files, folders and vectors left out, index arguments last in index order.
#include "CLI/ModuleDescription.h"

#include <map>
#include <string>
#include <vector>

namespace colonmap::testing {

std::vector<std::string> SlicerArguments(const cli::ModuleDescription& module,
                                         const std::map<std::string, std::string>& values);

}  // namespace colonmap::testing
