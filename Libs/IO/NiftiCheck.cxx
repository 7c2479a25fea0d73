#include "IO/NiftiCheck.h"
#include "IO/FileNames.h"

#include "Core/Error.h"

#include <zlib.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <string>

namespace colonmap::io {

namespace {

template <typename T>
T Field(const unsigned char* header, std::size_t offset, bool swap) {
  unsigned char b[sizeof(T)];
  std::memcpy(b, header + offset, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

// A gzip or plain file read as one stream (zlib reads plain files through, too).
struct Stream {
  gzFile file;
  explicit Stream(const std::string& path) : file(gzopen(path.c_str(), "rb")) {}
  ~Stream() {
    if (file) gzclose(file);
  }
  Stream(const Stream&) = delete;
  Stream& operator=(const Stream&) = delete;
};

}  // namespace

std::vector<int> CheckNiftiFile(const std::string& path, const std::string& what) {
  const std::string lower = LowerCase(path);
  if (!EndsWith(lower, ".nii") && !EndsWith(lower, ".nii.gz")) return {};
  Stream in(path);
  if (!in.file) throw InputError(what, path, "cannot be opened");
  unsigned char h[540] = {};
  const int got = gzread(in.file, h, 348);
  if (got < 348) throw InputError(what, path, "is too short for a NIfTI header");
  // NIfTI-1: sizeof_hdr 348, int16 dims, float32 pixdim, float32 vox_offset; NIfTI-2: 540, int64 and float64.
  const std::int32_t size = Field<std::int32_t>(h, 0, false);
  const std::int32_t swapped = Field<std::int32_t>(h, 0, true);
  const bool two = size == 540 || swapped == 540;
  const bool swap = two ? swapped == 540 : swapped == 348;
  if (!two && !swap && size != 348) throw InputError(what, path, "is not a NIfTI file (header size field)");
  if (two && gzread(in.file, h + 348, 540 - 348) < 540 - 348) throw InputError(what, path, "is too short for a NIfTI-2 header");
  double dim[8], pixdim[8], bitpix, offset;
  for (int k = 0; k < 8; ++k) {
    dim[k] = two ? static_cast<double>(Field<std::int64_t>(h, 16 + 8 * k, swap)) : Field<std::int16_t>(h, 40 + 2 * k, swap);
    pixdim[k] = two ? Field<double>(h, 104 + 8 * k, swap) : Field<float>(h, 76 + 4 * k, swap);
  }
  bitpix = two ? Field<std::int16_t>(h, 14, swap) : Field<std::int16_t>(h, 72, swap);
  offset = two ? static_cast<double>(Field<std::int64_t>(h, 168, swap)) : Field<float>(h, 108, swap);
  // dim[0] is checked as read (a NIfTI-2 int64): cast to int only once it is known to be 1..7.
  if (!(dim[0] >= 1 && dim[0] <= 7))
    throw InputError(what, path, "NIfTI header has " + std::to_string(static_cast<long long>(dim[0])) + " dimensions");
  const int n = static_cast<int>(dim[0]);
  for (int k = 1; k <= std::min(n, 3); ++k)
    // Negative values are left to ITK (its NIfTI library takes their magnitude).
    if (!std::isfinite(pixdim[k]) || pixdim[k] == 0.0)
      throw InputError(what, path, "voxel spacing " + std::to_string(k) + " in the NIfTI header is " +
                                       (std::isnan(pixdim[k]) ? std::string("NaN")
                                        : std::isinf(pixdim[k]) ? std::string("infinite")
                                                                : std::string("0")) +
                                       ", not a number of mm");
  std::vector<int> negative;
  for (int k = 1; k <= std::min(n, 3); ++k)
    if (pixdim[k] < 0.0) negative.push_back(k);
  double voxels = 1.0;
  for (int k = 1; k <= n; ++k) voxels *= std::max(1.0, dim[k]);
  const double bytes = std::max(offset, two ? 544.0 : 352.0) + voxels * bitpix / 8.0;
  if (!EndsWith(lower, ".gz")) {
    std::error_code ec;
    const double fileBytes = static_cast<double>(std::filesystem::file_size(path, ec));
    if (!ec && fileBytes < bytes)
      throw InputError(what, path, "is truncated: " + ByteCount(fileBytes) + " of " + ByteCount(bytes) + " bytes");
    return negative;
  }
  // A .nii.gz: read the stream through; it ends early, or with an error, when it is cut.
  double total = two ? 540.0 : 348.0;
  char buffer[1 << 16];
  for (;;) {
    const int r = gzread(in.file, buffer, sizeof buffer);
    if (r < 0) {
      int code = 0;
      throw InputError(what, path, std::string("is corrupt (") + gzerror(in.file, &code) + ")");
    }
    if (r == 0) break;
    total += r;
    if (total >= bytes) break;
  }
  if (total < bytes)
    throw InputError(what, path, "is truncated: " + ByteCount(total) + " of " + ByteCount(bytes) + " bytes");
  return negative;
}

}  // namespace colonmap::io
