#include "IO/MetaImageCheck.h"
#include "IO/FileNames.h"

#include "Core/Error.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace fs = std::filesystem;

namespace colonmap::io {
namespace {

double BytesOf(const std::string& type) {
  static const std::map<std::string, double> kBytes = {
      {"met_char", 1}, {"met_uchar", 1}, {"met_short", 2}, {"met_ushort", 2}, {"met_int", 4},
      {"met_uint", 4}, {"met_long", 4}, {"met_ulong", 4}, {"met_long_long", 8}, {"met_ulong_long", 8},
      {"met_float", 4}, {"met_double", 8}};
  const auto it = kBytes.find(type);
  return it == kBytes.end() ? 0.0 : it->second;
}

}  // namespace

std::vector<int> CheckMetaImageFile(const std::string& path, const std::string& what) {
  const std::string lower = LowerCase(path);
  if (!EndsWith(lower, ".mha") && !EndsWith(lower, ".mhd")) return {};
  std::ifstream in(path, std::ios::binary);
  std::map<std::string, std::string> header;
  std::string line, dataFile;
  for (int n = 0; n < 200 && std::getline(in, line); ++n) {
    const std::size_t eq = line.find('=');
    if (eq == std::string::npos) continue;
    const std::string key = LowerCase(Trim(line.substr(0, eq))), value = Trim(line.substr(eq + 1));
    header[key] = value;
    if (key == "elementdatafile") {  // the last header field: the voxels follow (LOCAL) or are elsewhere
      dataFile = value;
      break;
    }
  }
  // MetaIO reads "nan" in ElementSpacing as a failed field and says so in 4 lines of its own, then
  // ITK blames a missing file: refuse it here, in one line.
  for (const char* key : {"ElementSpacing", "Offset", "Origin", "Position", "TransformMatrix"}) {
    std::istringstream values(header[LowerCase(key)]);
    std::string token;
    while (values >> token) {
      char* end = nullptr;
      const double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v))
        throw InputError(what, path, "header field '" + std::string(key) + "' holds '" + token + "', not a finite number");
    }
  }
  const std::vector<int> negative = NegativeAxes(header["elementspacing"]);
  if (dataFile.empty() || LowerCase(header["compresseddata"]) == "true") return negative;  // zlib checks compressed data
  std::istringstream dims(header["dimsize"]);
  double voxels = 1.0, d;
  int count = 0;
  while (dims >> d) voxels *= d, ++count;
  const double bytesPerValue = BytesOf(LowerCase(header["elementtype"]));
  if (count == 0 || bytesPerValue == 0.0) return negative;  // ITK reports these itself
  const double channels = header.count("elementnumberofchannels") ? std::max(1.0, std::atof(header["elementnumberofchannels"].c_str())) : 1.0;
  const double needed = voxels * bytesPerValue * channels;
  double have = 0.0;
  std::string where = "its voxel data";
  std::error_code ec;
  if (LowerCase(dataFile) == "local") {
    const std::streamoff start = in.tellg();
    have = static_cast<double>(fs::file_size(path, ec)) - static_cast<double>(start);
  } else {
    if (dataFile.find(' ') != std::string::npos || LowerCase(dataFile) == "list") return negative;  // a file pattern or list
    const fs::path data = fs::path(path).parent_path() / dataFile;
    if (!fs::exists(data, ec)) throw InputError(what, path, "its voxel data file '" + dataFile + "' does not exist");
    have = static_cast<double>(fs::file_size(data, ec));
    where = "its voxel data file '" + dataFile + "'";
  }
  if (!ec && have < needed)
    throw InputError(what, path, "is truncated: " + where + " holds " + ByteCount(have) + " of " + ByteCount(needed) + " bytes");
  return negative;
}

}  // namespace colonmap::io
