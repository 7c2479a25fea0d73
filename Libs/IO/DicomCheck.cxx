#include "IO/DicomCheck.h"

#include "Core/Error.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace colonmap::io {
namespace {

constexpr std::uint32_t kUndefined = 0xFFFFFFFFu;

// A file cut short, or elements that do not nest: reported as "cut short" with the byte count.
struct Broken {
  std::string problem;
};

struct Syntax {
  bool explicitVR = true;
  bool bigEndian = false;
};

// What the check needs from a slice's top-level elements.
struct Slice {
  std::uint32_t rows = 0, columns = 0, bitsAllocated = 16, samples = 1, frames = 1;
  bool hasImageAttributes = false, hasPixelData = false;
  std::string series;
};

std::string Text(const unsigned char* p, std::size_t n) {
  std::string s(reinterpret_cast<const char*>(p), n);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
  while (!s.empty() && s.front() == ' ') s.erase(s.begin());
  return s;
}

class Walker {
 public:
  explicit Walker(const std::vector<unsigned char>& bytes) : b_(bytes) {}

  // The group 0002 elements after the preamble (always explicit VR little endian): the transfer
  // syntax of the data set, and where the data set starts.
  std::size_t Meta(std::size_t pos, std::string& transferSyntax) const {
    const Syntax meta{true, false};
    while (pos + 8 <= b_.size() && U16(pos, meta) == 0x0002) {
      std::uint32_t length = 0;
      const std::size_t value = Header(pos, meta, length, nullptr);
      if (length == kUndefined || length > b_.size() - value) throw Broken{"its file meta header is cut short"};
      if (U16(pos + 2, meta) == 0x0010) transferSyntax = Text(&b_[value], length);
      pos = value + length;
    }
    return pos;
  }

  // Elements from pos to the end of the file (top level, recorded in `slice`) or, nested, up to
  // an item delimiter; returns the position after it.
  std::size_t Elements(std::size_t pos, const Syntax& s, Slice* slice, bool nested) const {
    while (pos < b_.size()) {
      if (b_.size() - pos < 8) throw Broken{"an element header is cut short"};
      const std::uint16_t group = U16(pos, s), element = U16(pos + 2, s);
      if (group == 0xFFFE) {  // item tags carry no VR in any syntax
        const std::uint32_t length = U32(pos + 4, s);
        pos += 8;
        if (element == 0xE00D || element == 0xE0DD) {
          if (nested) return pos;
          continue;
        }
        pos = length == kUndefined ? Elements(pos, s, nullptr, true) : Skip(pos, length);
        continue;
      }
      std::uint32_t length = 0;
      std::string vr;
      const std::size_t value = Header(pos, s, length, &vr);
      const bool pixelData = group == 0x7FE0 && element == 0x0010;
      if (length == kUndefined) {
        // A sequence, or encapsulated (compressed) pixel data: items up to the sequence delimiter.
        // An undefined-length UN holds implicit VR little endian.
        pos = Items(value, vr == "UN" ? Syntax{false, false} : s);
        if (slice && pixelData) slice->hasPixelData = true;
        continue;
      }
      if (length > b_.size() - value)
        throw Broken{"element (" + Hex(group) + "," + Hex(element) + ") needs " + std::to_string(length) +
                     " bytes, the file holds " + std::to_string(b_.size() - value) + " more"};
      if (slice) Record(*slice, group, element, value, length, s);
      pos = value + length;
    }
    if (nested) throw Broken{"a sequence item is cut short"};
    return pos;
  }

 private:
  std::size_t Items(std::size_t pos, const Syntax& s) const {
    for (;;) {
      if (b_.size() - pos < 8) throw Broken{"a sequence is cut short"};
      if (U16(pos, s) != 0xFFFE) throw Broken{"a sequence is malformed"};
      const std::uint16_t element = U16(pos + 2, s);
      const std::uint32_t length = U32(pos + 4, s);
      pos += 8;
      if (element == 0xE0DD) return pos;
      pos = length == kUndefined ? Elements(pos, s, nullptr, true) : Skip(pos, length);
    }
  }

  std::size_t Skip(std::size_t pos, std::uint32_t length) const {
    if (length > b_.size() - pos) throw Broken{"a sequence item is cut short"};
    return pos + length;
  }

  // Reads the tag, VR and length at pos; returns where the value starts.
  std::size_t Header(std::size_t pos, const Syntax& s, std::uint32_t& length, std::string* vrOut) const {
    if (!s.explicitVR) {
      length = U32(pos + 4, s);
      return pos + 8;
    }
    const std::string vr(reinterpret_cast<const char*>(&b_[pos + 4]), 2);
    if (vrOut) *vrOut = vr;
    static constexpr const char* kLong[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"};
    if (std::find_if(std::begin(kLong), std::end(kLong), [&](const char* v) { return vr == v; }) != std::end(kLong)) {
      if (b_.size() - pos < 12) throw Broken{"an element header is cut short"};
      length = U32(pos + 8, s);
      return pos + 12;
    }
    length = U16(pos + 6, s);
    return pos + 8;
  }

  void Record(Slice& slice, std::uint16_t group, std::uint16_t element, std::size_t value, std::uint32_t length,
              const Syntax& s) const {
    if (group == 0x0028 && length >= 2) {
      const std::uint32_t v = U16(value, s);
      if (element == 0x0010) slice.rows = v, slice.hasImageAttributes = true;
      if (element == 0x0011) slice.columns = v, slice.hasImageAttributes = true;
      if (element == 0x0100) slice.bitsAllocated = v;
      if (element == 0x0002) slice.samples = v;
      if (element == 0x0008) slice.frames = static_cast<std::uint32_t>(std::max(1L, std::atol(Text(&b_[value], length).c_str())));
    }
    if (group == 0x0020 && element == 0x000E) slice.series = Text(&b_[value], length);
    if (group == 0x7FE0 && element == 0x0010) {
      slice.hasPixelData = true;
      // Native pixel data: its length is fixed by the header.
      const double needed = double(slice.rows) * slice.columns * slice.samples * slice.frames * slice.bitsAllocated / 8.0;
      if (length < needed)
        throw Broken{"its pixel data holds " + std::to_string(length) + " bytes, " + std::to_string(slice.rows) + " x " +
                     std::to_string(slice.columns) + " pixels of " + std::to_string(slice.bitsAllocated) +
                     " bits need " + std::to_string(static_cast<long long>(needed))};
    }
  }

  std::uint16_t U16(std::size_t p, const Syntax& s) const {
    return s.bigEndian ? std::uint16_t(b_[p] << 8 | b_[p + 1]) : std::uint16_t(b_[p] | b_[p + 1] << 8);
  }
  std::uint32_t U32(std::size_t p, const Syntax& s) const {
    const std::uint32_t a = U16(p, s), c = U16(p + 2, s);
    return s.bigEndian ? a << 16 | c : c << 16 | a;
  }
  static std::string Hex(std::uint16_t v) {
    char t[8];
    std::snprintf(t, sizeof t, "%04X", v);
    return t;
  }

  const std::vector<unsigned char>& b_;
};

enum class Kind { None, Part10, Headerless };

// A DICOM Part 10 file ("DICM" after the 128-byte preamble), or an old-style data set without
// preamble that GDCM also reads (it starts with a group 0002 or 0008 element); anything else is
// not DICOM and left alone.
Kind Sniff(const fs::path& file, std::vector<unsigned char>& bytes) {
  std::ifstream in(file, std::ios::binary);
  unsigned char head[132] = {};
  in.read(reinterpret_cast<char*>(head), sizeof head);
  const std::streamsize got = in.gcount();
  Kind kind = Kind::None;
  if (got == 132 && std::memcmp(head + 128, "DICM", 4) == 0) kind = Kind::Part10;
  else if (got >= 8 && (head[0] == 0x02 || head[0] == 0x08) && head[1] == 0x00) kind = Kind::Headerless;
  if (kind == Kind::None) return kind;
  in.clear();
  in.seekg(0);
  bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  return kind;
}

}  // namespace

int CheckDicomFolder(const std::string& folder, const std::string& what) {
  struct Seen {
    std::string name;
    std::uint32_t rows, columns;
  };
  std::map<std::string, std::vector<Seen>> series;
  int count = 0;
  std::error_code ec;
  std::vector<fs::path> files;
  for (const auto& entry : fs::directory_iterator(folder, ec))
    if (entry.is_regular_file(ec)) files.push_back(entry.path());
  std::sort(files.begin(), files.end());
  std::vector<unsigned char> bytes;
  for (const fs::path& file : files) {
    const Kind kind = Sniff(file, bytes);
    if (kind == Kind::None) continue;
    ++count;
    const std::string name = file.filename().string();
    Slice slice;
    try {
      Walker walk(bytes);
      std::string transferSyntax;
      std::size_t start = 0;
      if (kind == Kind::Part10 || bytes[0] == 0x02) {
        start = walk.Meta(kind == Kind::Part10 ? 132 : 0, transferSyntax);
        if (transferSyntax.empty()) throw Broken{"its file meta header is cut short or has no transfer syntax"};
      } else {
        // No meta header: the syntax is what the first element looks like (a VR of two capitals or not).
        const bool explicitVR = std::isupper(bytes[4]) && std::isupper(bytes[5]);
        transferSyntax = explicitVR ? "1.2.840.10008.1.2.1" : "1.2.840.10008.1.2";
      }
      if (transferSyntax == "1.2.840.10008.1.2.1.99") continue;  // deflated: GDCM inflates and checks it
      const Syntax s{transferSyntax != "1.2.840.10008.1.2", transferSyntax == "1.2.840.10008.1.2.2"};
      walk.Elements(start, s, &slice, false);
    } catch (const Broken& b) {
      throw InputError(what, folder, "slice file '" + name + "' is cut short or corrupt (" + b.problem + ", " +
                                         std::to_string(bytes.size()) + " bytes in all)");
    }
    if (slice.hasImageAttributes && !slice.hasPixelData)
      throw InputError(what, folder, "slice file '" + name + "' holds no pixel data (cut short at " +
                                         std::to_string(bytes.size()) + " bytes?)");
    if (slice.hasPixelData) series[slice.series].push_back({name, slice.rows, slice.columns});
  }
  // A slice of another size: named against the size most slices of its series have.
  for (const auto& [uid, slices] : series) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, int> sizes;
    for (const Seen& s : slices) ++sizes[{s.rows, s.columns}];
    if (sizes.size() < 2) continue;
    const auto common = std::max_element(sizes.begin(), sizes.end(), [](const auto& a, const auto& b) {
                          return a.second < b.second;
                        })->first;
    for (const Seen& s : slices)
      if (std::make_pair(s.rows, s.columns) != common)
        throw InputError(what, folder, "slice file '" + s.name + "' has " + std::to_string(s.rows) + " rows x " +
                                           std::to_string(s.columns) + " columns, the other slices of its series " +
                                           std::to_string(common.first) + " x " + std::to_string(common.second));
  }
  return count;
}

}  // namespace colonmap::io
