#include "IO/MeshIO.h"
#include "IO/FileNames.h"

#include "Core/Error.h"

#include <vtkCallbackCommand.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCommand.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkInputStream.h>
#include <vtkIntArray.h>
#include <vtkAbstractArray.h>
#include <vtkLZ4DataCompressor.h>
#include <vtkLZMADataCompressor.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataReader.h>
#include <vtkPolyDataWriter.h>
#include <vtkSTLReader.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkObjectFactory.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLDataParser.h>
#include <vtkXMLPolyDataReader.h>
#include <vtkXMLPolyDataWriter.h>
#include <vtkZLibDataCompressor.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <vector>

namespace fs = std::filesystem;

namespace colonmap::io {
namespace {

// Collects VTK errors of one reader/writer instead of letting them reach stderr (observers are
// per object: no global state is touched).
struct ErrorCollector {
  std::string message;
  vtkNew<vtkCallbackCommand> command;
  explicit ErrorCollector(vtkObject* object) {
    command->SetClientData(this);
    command->SetCallback([](vtkObject*, unsigned long event, void* client, void* data) {
      auto* self = static_cast<ErrorCollector*>(client);
      if (event == vtkCommand::ErrorEvent && self->message.empty() && data) {
        self->message = static_cast<const char*>(data);
        // "ERROR: In <source file>, line N\n<class> (0x..): <what went wrong>": the user needs the last part.
        if (const std::size_t at = self->message.find("): "); at != std::string::npos) self->message.erase(0, at + 3);
        for (auto& c : self->message) if (c == '\n') c = ' ';
        while (!self->message.empty() && self->message.back() == ' ') self->message.pop_back();
      }
    });
    object->AddObserver(vtkCommand::ErrorEvent, command);
    object->AddObserver(vtkCommand::WarningEvent, command);
  }
};

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
// - a string array holding more strings than it declares: VTK writes past its end;
// - cells declared without their offsets and connectivity, or a cell data array too short for its
//   cells: VTK dereferences a null pointer.
class XmlPolyDataCheck : public vtkXMLDataParser {
public:
  static XmlPolyDataCheck* New();
  vtkTypeMacro(XmlPolyDataCheck, vtkXMLDataParser);

  // The problem, or "" when there is none (or VTK itself will refuse the file).
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
    std::vector<std::pair<vtkXMLDataElement*, double>> strings, cellArrays;
    const auto add = [&](vtkXMLDataElement* array, double tuples, int components) {
      int type = VTK_CHAR;
      array->GetWordTypeAttribute("type", type);
      if (components <= 0 && !array->GetScalarAttribute("NumberOfComponents", components)) components = 1;
      const double values = std::max(0.0, tuples) * std::max(1, components);
      if (type == VTK_STRING) strings.emplace_back(array, values);
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
          else if (name == "PointData") add(array, points, 0);
          else if (name == "CellData") {
            add(array, cells, 0);
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
    // than it declares (a null std::string assigned). A writer ends each of its strings with a 0.
    for (const auto& [array, values] : strings) {
      const double found = CountStrings(array, fileSize * std::max(1.0, ratio));
      if (found > values) {
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

// VTK's own log (a parser's errors, with terminal colours, 10-49 lines) must not reach the user's
// stderr before our one line (issue 24): what a reader reports reaches us through the
// ErrorCollector's events and becomes that line; the rest goes nowhere.
void QuietVtkLog() {
  static const bool once = [] {
    vtkOutputWindow::GetInstance()->SetDisplayModeToNever();
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    return true;
  }();
  (void)once;
}

vtkSmartPointer<vtkPolyData> ReadPolyData(const std::string& path, const std::string& what) {
  QuietVtkLog();
  std::error_code ec;
  if (path.empty()) throw Error(what + ": no file given");
  if (!fs::exists(path, ec)) throw InputError(what, path, "file does not exist");
  if (fs::is_directory(path, ec)) throw InputError(what, path, "is a folder, not a surface file");
  const std::string ext = LowerCase(fs::path(path).extension().string());
  vtkSmartPointer<vtkPolyData> output;
  std::string error;
  if (ext == ".vtp") {
    vtkNew<XmlPolyDataCheck> check;
    if (const std::string problem = check->Check(path); !problem.empty()) throw InputError(what, path, problem);
    vtkNew<vtkXMLPolyDataReader> r;
    ErrorCollector errors(r);
    r->SetFileName(path.c_str());
    r->Update();
    error = errors.message;
    if (error.empty() && r->GetErrorCode() != 0) error = "read error";
    output = r->GetOutput();
  } else if (ext == ".vtk") {
    vtkNew<vtkPolyDataReader> r;
    ErrorCollector errors(r);
    r->SetFileName(path.c_str());
    if (!r->IsFilePolyData()) throw InputError(what, path, "is not a VTK polydata file");
    r->Update();
    error = errors.message;
    output = r->GetOutput();
  } else if (ext == ".stl") {
    vtkNew<vtkSTLReader> r;
    ErrorCollector errors(r);
    r->SetFileName(path.c_str());
    r->Update();
    error = errors.message;
    output = r->GetOutput();
  } else {
    throw InputError(what, path, "unknown surface format (expected .vtp, .vtk or .stl)");
  }
  if (error.find("No Points element") != std::string::npos) throw InputError(what, path, "holds no points");
  if (!error.empty()) throw InputError(what, path, "cannot be read (" + error + ")");
  if (!output || output->GetNumberOfPoints() == 0) throw InputError(what, path, "holds no points");
  return output;
}

void ReadArrays(vtkDataSetAttributes* attributes, std::map<std::string, DataArray>& arrays, vtkIdType n) {
  for (int a = 0; a < attributes->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = attributes->GetArray(a);
    if (!array || !array->GetName() || array->GetNumberOfTuples() != n) continue;
    DataArray d;
    d.integer = array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
    const int k = array->GetNumberOfComponents();
    d.values.resize(n, k);
    for (vtkIdType i = 0; i < n; ++i)
      for (int c = 0; c < k; ++c) d.values(i, c) = array->GetComponent(i, c);
    arrays[array->GetName()] = std::move(d);
  }
}

void WriteArrays(const std::map<std::string, DataArray>& arrays, vtkFieldData* attributes) {
  for (const auto& [name, d] : arrays) {
    vtkSmartPointer<vtkDataArray> array;
    if (d.integer) array = vtkSmartPointer<vtkIntArray>::New();
    else array = vtkSmartPointer<vtkDoubleArray>::New();
    array->SetName(name.c_str());
    array->SetNumberOfComponents(static_cast<int>(d.values.cols()));
    array->SetNumberOfTuples(d.values.rows());
    for (Eigen::Index i = 0; i < d.values.rows(); ++i)
      for (Eigen::Index c = 0; c < d.values.cols(); ++c)
        array->SetComponent(i, static_cast<int>(c), d.values(i, c));
    attributes->AddArray(array);
  }
}

// Field data: each array keeps its own number of tuples.
void ReadFieldArrays(vtkFieldData* field, FieldArrays& arrays) {
  if (!field) return;
  for (int a = 0; a < field->GetNumberOfArrays(); ++a) {
    vtkDataArray* array = field->GetArray(a);  // null for string arrays
    if (!array || !array->GetName()) continue;
    DataArray d;
    d.integer = array->GetDataType() != VTK_FLOAT && array->GetDataType() != VTK_DOUBLE;
    const vtkIdType n = array->GetNumberOfTuples();
    const int k = array->GetNumberOfComponents();
    d.values.resize(n, k);
    for (vtkIdType i = 0; i < n; ++i)
      for (int c = 0; c < k; ++c) d.values(i, c) = array->GetComponent(i, c);
    arrays[array->GetName()] = std::move(d);
  }
}

vtkSmartPointer<vtkPoints> ToPoints(const Eigen::MatrixXd& V) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) points->SetPoint(i, V(i, 0), V(i, 1), V(i, 2));
  return points;
}

Eigen::MatrixXd FromPoints(vtkPoints* points) {
  Eigen::MatrixXd V(points->GetNumberOfPoints(), 3);
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i) {
    double p[3];
    points->GetPoint(i, p);
    V.row(i) << p[0], p[1], p[2];
  }
  return V;
}

void WritePolyData(vtkPolyData* data, const std::string& path, const std::string& what) {
  QuietVtkLog();
  const std::string ext = LowerCase(fs::path(path).extension().string());
  std::string error;
  int ok = 0;
  if (ext == ".vtp") {
    vtkNew<vtkXMLPolyDataWriter> w;
    ErrorCollector errors(w);
    w->SetFileName(path.c_str());
    w->SetInputData(data);
    w->SetDataModeToAppended();
    w->SetCompressorTypeToZLib();
    ok = w->Write();
    error = errors.message;
  } else if (ext == ".vtk") {
    vtkNew<vtkPolyDataWriter> w;
    ErrorCollector errors(w);
    w->SetFileName(path.c_str());
    w->SetInputData(data);
    w->SetFileTypeToBinary();
    ok = w->Write();
    error = errors.message;
  } else {
    throw InputError(what, path, "unknown surface format (expected .vtp or .vtk)");
  }
  if (!ok || !error.empty()) throw InputError(what, path, "cannot be written (" + error + ")");
}

}  // namespace

namespace {

// What a reader checks at the door (issue 24): NaN or infinite coordinates make later stages
// crash or spin (a centroid of NaNs, a locator that never converges), and a triangle naming a
// point past the end reads memory that is not ours. NaN in a data array is refused too; +-inf is
// allowed there (a dilatation K of a degenerate face is +inf by definition).
void CheckFinitePoints(const Eigen::MatrixXd& V, const std::string& path, const std::string& what) {
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (!V.row(i).allFinite())
      throw InputError(what, path, "point " + std::to_string(i) + " has a NaN or infinite coordinate");
}

// A cell list as read, before it is walked (found by fuzzing): offsets that decrease made VTK's
// traversal read before the start of the connectivity, and a point id of 2^32 became point 0 when
// cast to int. Ids are checked here, as 64-bit numbers.
void CheckCells(vtkCellArray* cells, vtkIdType points, const std::string& kind, const std::string& path,
                const std::string& what) {
  if (points > std::numeric_limits<int>::max())
    throw InputError(what, path, "has " + std::to_string(points) + " points, more than we can index");
  if (!cells->IsValid())
    throw InputError(what, path, "has " + kind + " offsets that decrease or do not match the connectivity");
  vtkNew<vtkIdList> ids;
  for (vtkIdType cell = 0; cell < cells->GetNumberOfCells(); ++cell) {
    cells->GetCellAtId(cell, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      if (ids->GetId(k) < 0 || ids->GetId(k) >= points)
        throw InputError(what, path, kind + " " + std::to_string(cell) + " names point " + std::to_string(ids->GetId(k)) +
                                         ", but there are " + std::to_string(points) + " points");
  }
}

}  // namespace

void CheckMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what) {
  CheckFinitePoints(mesh.V, path, what);
  const Eigen::Index n = mesh.V.rows();
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      if (mesh.F(f, k) < 0 || mesh.F(f, k) >= n)
        throw InputError(what, path, "triangle " + std::to_string(f) + " names point " + std::to_string(mesh.F(f, k)) +
                                         ", but there are " + std::to_string(n) + " points");
  for (const auto* arrays : {&mesh.pointData, &mesh.cellData})
    for (const auto& [name, d] : *arrays)
      if (d.values.array().isNaN().any())
        throw InputError(what, path, "array " + name + " holds NaN values");
}

TriangleMesh ReadMesh(const std::string& path, const std::string& what) { return ReadMesh(path, what, nullptr); }

TriangleMesh ReadMesh(const std::string& path, const std::string& what, FieldArrays* fieldData) {
  vtkSmartPointer<vtkPolyData> data = ReadPolyData(path, what);
  TriangleMesh mesh;
  mesh.V = FromPoints(data->GetPoints());
  // Fan-triangulate polygons (strips are rare in our inputs and are not accepted).
  if (data->GetNumberOfStrips() > 0) throw InputError(what, path, "triangle strips are not supported");
  std::vector<Eigen::Vector3i> faces;
  std::vector<vtkIdType> faceSource;
  vtkCellArray* polys = data->GetPolys();
  CheckCells(polys, data->GetNumberOfPoints(), "polygon", path, what);
  vtkNew<vtkIdList> ids;
  polys->InitTraversal();
  for (vtkIdType cell = 0; polys->GetNextCell(ids); ++cell) {
    for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k) {
      faces.emplace_back(static_cast<int>(ids->GetId(0)), static_cast<int>(ids->GetId(k)),
                         static_cast<int>(ids->GetId(k + 1)));
      faceSource.push_back(cell);
    }
  }
  if (faces.empty()) throw InputError(what, path, "holds no triangles");
  mesh.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) mesh.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  ReadArrays(data->GetPointData(), mesh.pointData, data->GetNumberOfPoints());
  // Cell arrays are only meaningful when there are only polygons (VTK orders verts/lines first).
  if (data->GetNumberOfCells() == data->GetNumberOfPolys()) {
    std::map<std::string, DataArray> cells;
    ReadArrays(data->GetCellData(), cells, data->GetNumberOfCells());
    for (auto& [name, d] : cells) {
      DataArray expanded;
      expanded.integer = d.integer;
      expanded.values.resize(static_cast<Eigen::Index>(faceSource.size()), d.values.cols());
      for (std::size_t f = 0; f < faceSource.size(); ++f)
        expanded.values.row(static_cast<Eigen::Index>(f)) = d.values.row(faceSource[f]);
      mesh.cellData[name] = std::move(expanded);
    }
  }
  CheckMesh(mesh, path, what);
  if (fieldData) {
    fieldData->clear();
    ReadFieldArrays(data->GetFieldData(), *fieldData);
  }
  return mesh;
}

void WriteMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what) {
  WriteMesh(mesh, path, what, FieldArrays{});
}

void WriteMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what, const FieldArrays& fieldData) {
  vtkNew<vtkPolyData> data;
  data->SetPoints(ToPoints(mesh.V));
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(mesh.F.rows(), 3 * mesh.F.rows());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const vtkIdType ids[3] = {static_cast<vtkIdType>(mesh.F(f, 0)), static_cast<vtkIdType>(mesh.F(f, 1)),
                             static_cast<vtkIdType>(mesh.F(f, 2))};
    polys->InsertNextCell(3, ids);
  }
  data->SetPolys(polys);
  WriteArrays(mesh.pointData, data->GetPointData());
  WriteArrays(mesh.cellData, data->GetCellData());
  WriteArrays(fieldData, data->GetFieldData());
  WritePolyData(data, path, what);
}

PolylineSet ReadPolylines(const std::string& path, const std::string& what) {
  vtkSmartPointer<vtkPolyData> data = ReadPolyData(path, what);
  PolylineSet set;
  auto* names = vtkStringArray::SafeDownCast(data->GetCellData()->GetAbstractArray("Name"));
  vtkCellArray* lines = data->GetLines();
  CheckCells(lines, data->GetNumberOfPoints(), "line", path, what);
  vtkNew<vtkIdList> ids;
  lines->InitTraversal();
  for (vtkIdType cell = 0; lines->GetNextCell(ids); ++cell) {
    Polyline line;
    const vtkIdType n = ids->GetNumberOfIds();
    line.closed = n > 2 && ids->GetId(0) == ids->GetId(n - 1);
    const vtkIdType count = line.closed ? n - 1 : n;
    line.points.resize(count, 3);
    for (vtkIdType k = 0; k < count; ++k) {
      if (ids->GetId(k) < 0 || ids->GetId(k) >= data->GetNumberOfPoints())
        throw InputError(what, path, "line " + std::to_string(cell) + " names point " + std::to_string(ids->GetId(k)) +
                                         ", but there are " + std::to_string(data->GetNumberOfPoints()) + " points");
      double p[3];
      data->GetPoint(ids->GetId(k), p);
      line.points.row(k) << p[0], p[1], p[2];
    }
    CheckFinitePoints(line.points, path, what);
    if (names && cell < names->GetNumberOfValues()) line.name = names->GetValue(cell);
    set.lines.push_back(std::move(line));
  }
  if (set.lines.empty()) throw InputError(what, path, "holds no polylines");
  ReadArrays(data->GetPointData(), set.pointData, data->GetNumberOfPoints());
  // Per-line arrays (SegmentId, IsCut, ...): the cells are the lines.
  if (data->GetNumberOfCells() == data->GetNumberOfLines())
    ReadArrays(data->GetCellData(), set.cellData, data->GetNumberOfCells());
  return set;
}

void WritePolylines(const PolylineSet& set, const std::string& path, const std::string& what) {
  Eigen::Index total = 0;
  for (const auto& l : set.lines) total += l.points.rows();
  Eigen::MatrixXd V(total, 3);
  vtkNew<vtkCellArray> cells;
  vtkNew<vtkStringArray> names;
  names->SetName("Name");
  Eigen::Index offset = 0;
  for (const auto& l : set.lines) {
    V.middleRows(offset, l.points.rows()) = l.points;
    std::vector<vtkIdType> ids;
    for (Eigen::Index k = 0; k < l.points.rows(); ++k) ids.push_back(offset + k);
    if (l.closed && !ids.empty()) ids.push_back(offset);
    cells->InsertNextCell(static_cast<vtkIdType>(ids.size()), ids.data());
    names->InsertNextValue(l.name);
    offset += l.points.rows();
  }
  vtkNew<vtkPolyData> data;
  data->SetPoints(ToPoints(V));
  data->SetLines(cells);
  data->GetCellData()->AddArray(names);
  WriteArrays(set.pointData, data->GetPointData());
  WriteArrays(set.cellData, data->GetCellData());
  WritePolyData(data, path, what);
}

}  // namespace colonmap::io
