#pragma once
// Slicer point lists <-> MarkupList. Reads .mrk.json (markups schema v1.0.3, LPS or RAS) and
// .fcsv (Slicer's CSV, LPS or RAS header); positions come back in LPS. Writes .mrk.json in LPS
// (valid against ../shared/schemas/markups-schema-v1.0.3.json) or .fcsv.
#include "Core/Markups.h"

#include <string>

namespace colonmap::io {

MarkupList ReadMarkups(const std::string& path, const std::string& what);
void WriteMarkups(const MarkupList& markups, const std::string& path, const std::string& what);

// Writes a JSON document (nlohmann dump of `jsonText`) atomically is the caller's job; this only
// writes text to a path and reports failure in the standard way.
void WriteText(const std::string& text, const std::string& path, const std::string& what);

}  // namespace colonmap::io
