#include "IO/NrrdCheck.h"
#include "IO/FileNames.h"

#include "Core/Error.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace colonmap::io {

namespace {

// Bytes per value of a NRRD "type:" (its spellings: "short", "int16", "unsigned short", "uint16_t",
// ...); 0 for "block" or an unknown type, which ITK reports itself.
double BytesOfType(std::string type) {
  type = LowerCase(type);
  if (type == "float") return 4;
  if (type == "double") return 8;
  if (type.find("long") != std::string::npos || type.find("64") != std::string::npos) return 8;
  if (type.find("short") != std::string::npos || type.find("16") != std::string::npos) return 2;
  if (type.find("char") != std::string::npos || type.find("8") != std::string::npos) return 1;
  if (type.find("int") != std::string::npos || type.find("32") != std::string::npos) return 4;
  return 0;
}

// Raw voxel data cut short (in the file after the header, or in the detached "data file:"): ITK
// would find it only when the voxels are read, a minute into a pipeline (issue 24). Compressed
// encodings are left to zlib; skips, lists and file patterns to ITK.
void CheckRawDataSize(const std::string& path, const std::string& what, const std::map<std::string, std::string>& f,
                      std::streamoff dataStart) {
  const auto field = [&](const char* k) {
    const auto it = f.find(k);
    return it == f.end() ? std::string() : it->second;
  };
  if (LowerCase(field("encoding")) != "raw" || f.count("line skip") || f.count("lineskip") || f.count("byte skip") ||
      f.count("byteskip"))
    return;
  std::istringstream sizes(field("sizes"));
  double voxels = 1.0, d;
  int axes = 0;
  while (sizes >> d) voxels *= d, ++axes;
  const double bytesPerValue = BytesOfType(field("type"));
  if (axes == 0 || bytesPerValue == 0.0) return;
  const double needed = voxels * bytesPerValue;
  std::string dataFile = field("data file");
  if (dataFile.empty()) dataFile = field("datafile");
  std::error_code ec;
  double have = 0.0;
  std::string where = "its voxel data";
  if (dataFile.empty()) {
    if (dataStart < 0) return;
    have = static_cast<double>(std::filesystem::file_size(path, ec)) - static_cast<double>(dataStart);
  } else {
    if (dataFile.find(' ') != std::string::npos || LowerCase(dataFile).rfind("list", 0) == 0) return;
    const std::filesystem::path data = std::filesystem::path(path).parent_path() / dataFile;
    if (!std::filesystem::exists(data, ec)) throw InputError(what, path, "its voxel data file '" + dataFile + "' does not exist");
    have = static_cast<double>(std::filesystem::file_size(data, ec));
    where = "its voxel data file '" + dataFile + "'";
  }
  if (!ec && have < needed)
    throw InputError(what, path, "is truncated: " + where + " holds " + ByteCount(have) + " of " + ByteCount(needed) + " bytes");
}

}  // namespace

std::vector<int> CheckNrrdHeader(const std::string& path, const std::string& what) {
  const std::string lower = LowerCase(path);
  if (!EndsWith(lower, ".nrrd") && !EndsWith(lower, ".nhdr")) return {};
  std::vector<int> negative;
  std::ifstream in(path, std::ios::binary);
  std::map<std::string, std::string> fields;  // for the size check: the raw field values
  std::string line;
  bool headerEnded = false;
  for (int n = 0; n < 200 && std::getline(in, line); ++n) {
    if (line.empty() || line == "\r") {
      headerEnded = true;
      break;
    }
    // "field: value" (a "key:=value" pair or a "#" comment is not a field).
    if (const std::size_t colon = line.find(": "); colon != std::string::npos && line[0] != '#')
      fields[LowerCase(Trim(line.substr(0, colon)))] = Trim(line.substr(colon + 2));
    line = LowerCase(line);
    for (const char* field : {"spacings:", "space directions:", "space origin:"}) {
      if (line.rfind(field, 0) != 0) continue;
      if (line.find("nan") != std::string::npos)
        throw InputError(what, path, std::string("header field '") + field + "' holds NaN");
      // "inf" or an overflowing "1e999": Teem reads an infinite spacing or origin, and nothing
      // after it is measured right (found by fuzzing).
      std::string values = line.substr(std::strlen(field));
      for (char& c : values)
        if (c == '(' || c == ')' || c == ',') c = ' ';
      std::istringstream tokens(values);
      std::string token;
      while (tokens >> token) {
        char* end = nullptr;
        const double v = std::strtod(token.c_str(), &end);
        if (end != token.c_str() && *end == '\0' && !std::isfinite(v))
          throw InputError(what, path, std::string("header field '") + field + "' holds an infinite number ('" + token + "')");
      }
    }
    if (line.rfind("spacings:", 0) == 0) negative = NegativeAxes(line.substr(9));
  }
  const std::streamoff dataStart = headerEnded ? static_cast<std::streamoff>(in.tellg()) : -1;
  CheckRawDataSize(path, what, fields, dataStart);
  return negative;
}

}  // namespace colonmap::io
