#include "IO/XmlPolyDataCheck.h"
#include "IO/FileNames.h"

#include <vtkAbstractArray.h>
#include <vtkDataCompressor.h>
#include <vtkInputStream.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkZLibDataCompressor.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

namespace fs = std::filesystem;

namespace colonmap::io {
namespace {

// What VTK's XML reader (9.1) trusts and should not, found by fuzzing (issue 24, docs/fuzzing.md),
// checked before it reads the file, with VTK's own parser, streams and positions on the same bytes:
// - a FieldData array of a type VTK does not know: vtkXMLReader dereferences a null array;
// - a Points array without 3 components: VTK leaks the points (about 500 bytes); fewer than 1 or
//   more components than the file has bytes: VTK sizes per-component storage by the number;
// - a compressor VTK does not know: it says so, then reads the compressed data as raw;
// - a compressed array's header (block count, block sizes): vtkXMLDataParser allocates by it, up to
//   2^62 bytes from a 4 KB file. Refused when no writer can have written it: more block sizes than
//   the file has bytes, a last block larger than the others (VTK's size arithmetic wraps around), a
//   block larger than the file, or a block that would decompress beyond the compressor's best
//   ratio (deflate 1032:1, LZ4 255:1, LZMA about 7000:1; the bound used is 16384:1);
// - counts (NumberOfPoints, ..., NumberOfTuples, the last cell offset): arrays are allocated by them
//   before their data are read, so their values must fit in the file;
// - a string array holding more strings than it declares: VTK writes past its end; a point or
//   cell data string array holding fewer strings than there are points or cells: VTK reads
//   through a null pointer;
// - cells declared without their offsets and connectivity, or a cell data array too short for its
//   cells: VTK dereferences a null pointer;
// - two arrays of one name in point, cell or field data: VTK makes the first only and reads the
//   second into the array that was not made (a null dereference for cell data).
class XmlPolyDataCheck : public vtkXMLDataParser {
public:
  static XmlPolyDataCheck* New();
  vtkTypeMacro(XmlPolyDataCheck, vtkXMLDataParser);

  std::string Check(const std::string& path) {
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(path, ec);
    if (ec) return {};
    std::ifstream in(path, std::ios::binary);
    this->SetStream(&in);
    std::string problem;
    if (this->Parse() && this->GetRootElement()) {
      // VTK reports a compressor it does not know, then reads the data as not compressed.
      if (Ratio() < 0)
        problem = "names a compressor VTK does not know ('" +
                  std::string(this->GetRootElement()->GetAttribute("compressor")) + "')";
      if (problem.empty()) problem = CheckStructure(static_cast<double>(size));
      if (problem.empty()) problem = CheckArrays(static_cast<double>(size));
      if (problem.empty()) problem = CheckSizes(static_cast<double>(size));
    }
    this->SetStream(nullptr);
    return problem;
  }

private:
  std::string CheckStructure(double fileSize) {
    std::vector<vtkXMLDataElement*> todo{this->GetRootElement()};
    while (!todo.empty()) {
      vtkXMLDataElement* e = todo.back();
      todo.pop_back();
      for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) todo.push_back(e->GetNestedElement(i));
      // VTK sizes per-component storage by NumberOfComponents (-13 ended in std::length_error, 10^75
      // in a loop over 2^31 components); each component of a tuple needs at least a byte of the file.
      if (const char* text = e->GetAttribute("NumberOfComponents")) {
        char* end = nullptr;
        const double declared = std::strtod(text, &end);
        if (end != text && !(declared >= 1 && declared <= fileSize)) {
          const char* name = e->GetAttribute("Name");
          return "array '" + std::string(name ? name : "") + "' declares " + std::string(text) + " components";
        }
      }
      // A piece that declares cells has their offsets and connectivity (VTK dereferences a null
      // array reading cell data without them).
      for (const char* kind : {"Verts", "Lines", "Strips", "Polys"}) {
        long long cells = 0;
        const std::string count = "NumberOf" + std::string(kind);
        if (std::strcmp(e->GetName(), "Piece") != 0 || !e->GetScalarAttribute(count.c_str(), cells) || cells < 1)
          continue;
        vtkXMLDataElement* list = e->FindNestedElementWithName(kind);
        if (!list || !list->FindNestedElementWithNameAndAttribute("DataArray", "Name", "offsets") ||
            !list->FindNestedElementWithNameAndAttribute("DataArray", "Name", "connectivity"))
          return "declares " + std::to_string(cells) + " " + kind + " but has no " + kind + " offsets and connectivity";
      }
      const bool fieldData = std::strcmp(e->GetName(), "FieldData") == 0;
      const bool points = std::strcmp(e->GetName(), "Points") == 0;
      // Two arrays of one name in point, cell or field data: VTK creates the first only, then reads
      // the second into an array that does not exist (a null dereference for cell data).
      if (fieldData || std::strcmp(e->GetName(), "PointData") == 0 || std::strcmp(e->GetName(), "CellData") == 0) {
        std::vector<std::string> names;
        for (int i = 0; i < e->GetNumberOfNestedElements(); ++i)
          if (const char* name = e->GetNestedElement(i)->GetAttribute("Name")) names.emplace_back(name);
        std::sort(names.begin(), names.end());
        if (const auto twice = std::adjacent_find(names.begin(), names.end()); twice != names.end())
          return std::string(e->GetName()) + " has two arrays named '" + *twice + "'";
      }
      for (int i = 0; (fieldData || points) && i < e->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* array = e->GetNestedElement(i);
        const char* name = array->GetAttribute("Name");
        int type = 0, components = 0;
        if (fieldData && !array->GetWordTypeAttribute("type", type)) {
          const char* t = array->GetAttribute("type");
          return "field data array '" + std::string(name ? name : "") + "' has no type VTK knows ('" +
                 (t ? t : "") + "')";
        }
        if (points && !(array->GetScalarAttribute("NumberOfComponents", components) && components == 3))
          return "points array '" + std::string(name ? name : "") + "' does not have 3 components";
      }
    }
    return {};
  }

  // An appended array's offset (one that does not parse is 0, as for VTK); false when the appended
  // data position plus the offset is outside the file's range of positions (VTK cannot seek there).
  bool Offset(vtkXMLDataElement* array, long long& offset) {
    offset = 0;
    array->GetScalarAttribute("offset", offset);
    const long long base = this->AppendedDataPosition;
    return offset >= -base && offset <= std::numeric_limits<long long>::max() - base;
  }

  // The compressor's best ratio, 0 without compression, -1 for a compressor VTK does not know.
  double Ratio() {
    const char* compressor = this->GetRootElement()->GetAttribute("compressor");
    if (!compressor) return 0;
    if (std::strcmp(compressor, "vtkZLibDataCompressor") == 0) return 1032;
    if (std::strcmp(compressor, "vtkLZ4DataCompressor") == 0) return 256;
    if (std::strcmp(compressor, "vtkLZMADataCompressor") == 0) return 16384;
    return -1;
  }

  std::string CheckArrays(double fileSize) {
    const double ratio = Ratio();
    if (ratio == 0) return {};  // no compression headers
    std::vector<vtkXMLDataElement*> todo{this->GetRootElement()};
    while (!todo.empty()) {
      vtkXMLDataElement* e = todo.back();
      todo.pop_back();
      for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) todo.push_back(e->GetNestedElement(i));
      // As vtkXMLReader::ReadArrayValues: an "offset" makes an array appended whatever its name
      // or format says (an offset that does not parse is 0), otherwise format="binary" is inline.
      const char* format = e->GetAttribute("format");
      this->Stream->clear();  // a previous header may have ended at the end of the file
      if (e->GetAttribute("offset")) {
        long long offset = 0;
        if (!Offset(e, offset)) continue;
        this->DataStream = this->AppendedDataStream;
        this->SeekG(this->AppendedDataPosition + offset);
      } else if (format && std::strcmp(format, "binary") == 0) {
        this->DataStream = this->InlineDataStream;
        this->SeekInlineDataPosition(e);
      } else {
        continue;
      }
      const char* name = e->GetAttribute("Name");
      std::string problem = CheckHeader(fileSize, ratio);
      if (!problem.empty()) return "compressed array '" + std::string(name ? name : "") + "' " + problem;
    }
    return {};
  }

  // Every array VTK allocates by a count the file declares: the points, point and cell data, field
  // data, cell offsets and connectivity (as long as the last offset says). Their values must be in
  // the file: at least a character each in ascii, their bytes in binary, their bytes over the
  // compressor's best ratio when compressed (a bit array: 8 values a byte).
  std::string CheckSizes(double fileSize) {
    const double ratio = Ratio();
    if (ratio > 0) {
      vtkSmartPointer<vtkDataCompressor> compressor;
      if (ratio == 1032) compressor = vtkSmartPointer<vtkZLibDataCompressor>::New();
      else if (ratio == 256) compressor = vtkSmartPointer<vtkLZ4DataCompressor>::New();
      else compressor = vtkSmartPointer<vtkLZMADataCompressor>::New();
      this->SetCompressor(compressor);  // to read a last offset (its headers are checked)
    }
    double needed = 0;
    struct Strings {
      vtkXMLDataElement* array;
      double values;
      bool perPointOrCell;  // point or cell data: exactly one string per value
    };
    std::vector<Strings> strings;
    std::vector<std::pair<vtkXMLDataElement*, double>> cellArrays;
    const auto add = [&](vtkXMLDataElement* array, double tuples, int components, bool perPointOrCell = false) {
      int type = VTK_CHAR;
      array->GetWordTypeAttribute("type", type);
      if (components <= 0 && !array->GetScalarAttribute("NumberOfComponents", components)) components = 1;
      const double values = std::max(0.0, tuples) * std::max(1, components);
      if (type == VTK_STRING) strings.push_back({array, values, perPointOrCell});
      const bool ascii = !array->GetAttribute("offset") &&
                         !(array->GetAttribute("format") && std::strcmp(array->GetAttribute("format"), "binary") == 0);
      const double bytes = type == VTK_BIT ? values / 8 : values * std::max(1, vtkAbstractArray::GetDataTypeSize(type));
      needed += ascii ? values : ratio > 0 ? bytes / ratio : bytes;
    };
    const auto count = [](vtkXMLDataElement* e, const char* name) {
      long long n = 0;
      e->GetScalarAttribute(name, n);
      return static_cast<double>(n);
    };
    std::vector<vtkXMLDataElement*> todo{this->GetRootElement()};
    while (!todo.empty()) {
      vtkXMLDataElement* e = todo.back();
      todo.pop_back();
      for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) todo.push_back(e->GetNestedElement(i));
      if (std::strcmp(e->GetName(), "FieldData") == 0)
        for (int i = 0; i < e->GetNumberOfNestedElements(); ++i)
          add(e->GetNestedElement(i), count(e->GetNestedElement(i), "NumberOfTuples"), 0);
      if (std::strcmp(e->GetName(), "Piece") != 0) continue;
      const double points = count(e, "NumberOfPoints");
      const char* kinds[] = {"Verts", "Lines", "Strips", "Polys"};
      double cells = 0;
      for (const char* kind : kinds) cells += std::max(0.0, count(e, ("NumberOf" + std::string(kind)).c_str()));
      for (int i = 0; i < e->GetNumberOfNestedElements(); ++i) {
        vtkXMLDataElement* part = e->GetNestedElement(i);
        const std::string name = part->GetName();
        for (int j = 0; j < part->GetNumberOfNestedElements(); ++j) {
          vtkXMLDataElement* array = part->GetNestedElement(j);
          if (name == "Points") add(array, points, 3);
          else if (name == "PointData") add(array, points, 0, true);
          else if (name == "CellData") {
            add(array, cells, 0, true);
            cellArrays.emplace_back(array, cells);
          }
        }
        for (const char* kind : kinds) {
          if (name != kind) continue;
          const double n = count(e, ("NumberOf" + name).c_str());
          vtkXMLDataElement* offsets = part->FindNestedElementWithNameAndAttribute("DataArray", "Name", "offsets");
          vtkXMLDataElement* connectivity =
              part->FindNestedElementWithNameAndAttribute("DataArray", "Name", "connectivity");
          if (!offsets || !connectivity || n < 1) continue;
          add(offsets, n, 1);
          if (needed > fileSize + 1024) break;  // the last offset is only read where it can be
          add(connectivity, LastOffset(offsets, static_cast<vtkTypeUInt64>(n)), 1);
        }
      }
    }
    if (needed > fileSize + 1024)
      return "declares arrays that need at least " + ByteCount(needed) + " bytes of the file, which has " +
             ByteCount(fileSize);
    // vtkXMLDataReader dereferences a null pointer when a cell data array is too short (an empty
    // ascii array for one cell is enough): its last value must be there.
    for (const auto& [array, cells] : cellArrays) {
      int components = 1, type = 0;
      array->GetScalarAttribute("NumberOfComponents", components);
      array->GetWordTypeAttribute("type", type);
      const double values = cells * std::max(1, components);
      double last = 0;
      if (values >= 1 && type != VTK_STRING && type != VTK_BIT &&
          !ReadValue(array, static_cast<vtkTypeUInt64>(values - 1), last)) {
        const char* name = array->GetAttribute("Name");
        return "cell data array '" + std::string(name ? name : "") + "' does not hold the " + ByteCount(values) +
               " values its cells need";
      }
    }
    // vtkXMLReader writes an empty string past the end of a string array that holds more strings
    // than it declares (a null std::string assigned), and reads through a null pointer when a point
    // or cell data string array is short. A writer ends each of its strings with a 0.
    for (const auto& [array, values, perPointOrCell] : strings) {
      const double found = CountStrings(array, fileSize * std::max(1.0, ratio));
      if (found > values || (perPointOrCell && found < values)) {
        const char* name = array->GetAttribute("Name");
        return "string array '" + std::string(name ? name : "") + "' holds " + ByteCount(found) + " strings, not " +
               ByteCount(values);
      }
    }
    return {};
  }

  // The strings (ends of string, 0 bytes) in a string array's data, read as VTK reads them, a
  // megabyte at a time, at most `limit` bytes.
  double CountStrings(vtkXMLDataElement* array, double limit) {
    const char* format = array->GetAttribute("format");
    const bool appended = array->GetAttribute("offset") != nullptr;
    const bool ascii = !appended && !(format && std::strcmp(format, "binary") == 0);
    long long offset = 0;
    if (appended && !Offset(array, offset)) return 0;
    std::vector<char> chunk(std::size_t{1} << 20);
    double zeros = 0;
    for (vtkTypeUInt64 start = 0; static_cast<double>(start) < limit;) {
      this->Stream->clear();
      const std::size_t got = appended ? this->ReadAppendedData(offset, chunk.data(), start, chunk.size())
                                       : this->ReadInlineData(array, ascii, chunk.data(), start, chunk.size());
      zeros += static_cast<double>(std::count(chunk.begin(), chunk.begin() + static_cast<std::ptrdiff_t>(got), '\0'));
      if (got < chunk.size()) break;
      start += got;
    }
    return zeros;
  }

  // Value `index` of an array, read as VTK reads it; false when it cannot be read.
  bool ReadValue(vtkXMLDataElement* array, vtkTypeUInt64 index, double& value) {
    int type = 0;
    if (!array->GetWordTypeAttribute("type", type) || type == VTK_BIT || type == VTK_STRING ||
        vtkAbstractArray::GetDataTypeSize(type) > 8)
      return false;
    unsigned char word[8] = {};
    this->Stream->clear();
    std::size_t got = 0;
    if (array->GetAttribute("offset")) {
      long long offset = 0;
      if (!Offset(array, offset)) return false;
      got = this->ReadAppendedData(offset, word, index, 1, type);
    } else {
      const char* format = array->GetAttribute("format");
      got = this->ReadInlineData(array, !(format && std::strcmp(format, "binary") == 0), word, index, 1, type);
    }
    if (got != 1) return false;
    switch (type) {
      vtkTemplateMacro(value = static_cast<double>(*reinterpret_cast<VTK_TT*>(word)));
    }
    return true;
  }

  // The value VTK takes as the length of the connectivity; 0 when it cannot be read.
  double LastOffset(vtkXMLDataElement* offsets, vtkTypeUInt64 n) {
    double last = 0;
    return ReadValue(offsets, n - 1, last) ? last : 0;
  }

  std::string CheckHeader(double fileSize, double ratio) {
    const std::size_t word = this->HeaderType == 64 ? 8 : 4;
    const auto get = [word](const unsigned char* p) -> std::uint64_t {
      if (word == 8) {
        std::uint64_t v;
        std::memcpy(&v, p, 8);
        return v;
      }
      std::uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    };
    this->DataStream->SetStream(this->Stream);
    this->DataStream->StartReading();
    unsigned char head[24];
    std::string problem;
    if (this->DataStream->Read(head, 3 * word) == 3 * word) {
      this->PerformByteSwap(head, 3, word);
      const std::uint64_t blocks = get(head), blockSize = get(head + word), lastSize = get(head + 2 * word);
      if (static_cast<double>(blocks) * static_cast<double>(word) > fileSize) {
        problem = "has a header declaring " + std::to_string(blocks) + " blocks, more than the file can hold";
      } else if (lastSize > blockSize || (blocks == 0 && lastSize != 0 && lastSize != blockSize)) {
        // VTK takes the size of the data as blocks * blockSize - blockSize + lastSize.
        problem = "has a header declaring " + std::to_string(blocks) + " blocks of " + std::to_string(blockSize) +
                  " bytes and a last block of " + std::to_string(lastSize) + " bytes";
      } else {
        std::vector<unsigned char> sizes(blocks * word);
        if (blocks > 0 && this->DataStream->Read(sizes.data(), sizes.size()) == sizes.size()) {
          this->PerformByteSwap(sizes.data(), blocks, word);
          for (std::uint64_t b = 0; b < blocks && problem.empty(); ++b) {
            const double compressed = static_cast<double>(get(sizes.data() + b * word));
            const double uncompressed = static_cast<double>(b + 1 < blocks || lastSize == 0 ? blockSize : lastSize);
            if (compressed > fileSize)
              problem = "has a block of " + ByteCount(compressed) + " bytes, larger than the file";
            else if (uncompressed > ratio * compressed + 1024)
              problem = "has a block of " + ByteCount(compressed) + " bytes said to decompress to " +
                        ByteCount(uncompressed) + " bytes";
          }
        }
      }
    }
    this->DataStream->EndReading();
    return problem;
  }
};
vtkStandardNewMacro(XmlPolyDataCheck);

}  // namespace

std::string CheckXmlPolyData(const std::string& path) {
  vtkNew<XmlPolyDataCheck> check;
  return check->Check(path);
}

}  // namespace colonmap::io
