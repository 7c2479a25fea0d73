// The header checks run before ITK reads an image: CheckNrrdHeader, CheckMetaImageFile and
// CheckNiftiFile. The first byte chooses the check (N: .nrrd, n: .nhdr, M/O/D/E: .mha, otherwise
// NIfTI: .nii.gz when the rest starts with the gzip magic, else .nii); the rest is the file.
// Contract when a check returns: axes in 1..3 (we read 3-D images), increasing; a NRRD
// spacings/space directions/space origin field holds no NaN or infinite number (ITK would
// silently take it as unknown or infinite).
#include "FuzzCommon.h"
#include "IO/MetaImageCheck.h"
#include "IO/NiftiCheck.h"
#include "IO/NrrdCheck.h"
#include "Core/Error.h"

#include <cctype>
#include <cmath>
#include <cstring>
#include <sstream>
#include <vector>

namespace {

void CheckAxes(const std::vector<int>& axes) {
  for (std::size_t i = 0; i < axes.size(); ++i) {
    if (axes[i] < 1 || axes[i] > 3) fuzz::Violation("negative-spacing axis out of range");
    if (i > 0 && axes[i] <= axes[i - 1]) fuzz::Violation("negative-spacing axes not increasing");
  }
}

// An oracle independent of the check: any token of the geometry fields that strtod reads whole
// as a non-finite number (what Teem's parser would take).
void CheckNrrdGeometry(const uint8_t* data, size_t size) {
  std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
  std::string line;
  for (int n = 0; n < 200 && std::getline(in, line) && !line.empty() && line != "\r"; ++n) {
    std::string lower = line;
    for (auto& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    for (const char* field : {"spacings:", "space directions:", "space origin:"}) {
      if (lower.rfind(field, 0) != 0) continue;
      std::string values = lower.substr(std::strlen(field));
      for (auto& c : values)
        if (c == '(' || c == ')' || c == ',') c = ' ';
      std::istringstream tokens(values);
      std::string t;
      while (tokens >> t) {
        char* end = nullptr;
        const double v = std::strtod(t.c_str(), &end);
        if (end != t.c_str() && *end == '\0' && !std::isfinite(v))
          fuzz::Violation("NRRD geometry field with a non-finite number accepted");
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const uint8_t kind = data[0];
  ++data, --size;
  std::string ext;
  if (kind == 'N') ext = ".nrrd";
  else if (kind == 'n') ext = ".nhdr";
  else if (kind == 'M' || kind == 'O' || kind == 'D' || kind == 'E') ext = kind == 'M' ? ".mha" : ".mhd";
  else ext = size >= 2 && data[0] == 0x1f && data[1] == 0x8b ? ".nii.gz" : ".nii";
  const std::string path = fuzz::WriteInput(data, size, ext);
  try {
    if (ext == ".nrrd" || ext == ".nhdr") {
      CheckAxes(colonmap::io::CheckNrrdHeader(path, "image"));
      CheckNrrdGeometry(data, size);
    } else if (ext == ".mha" || ext == ".mhd") {
      CheckAxes(colonmap::io::CheckMetaImageFile(path, "image"));
    } else {
      const std::vector<int> axes = colonmap::io::CheckNiftiFile(path, "image");
      CheckAxes(axes);
    }
  } catch (const colonmap::Error&) {
  }
  return 0;
}
