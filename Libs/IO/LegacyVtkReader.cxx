#include "IO/LegacyVtkReader.h"
#include "IO/FileNames.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkTypeInt64Array.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>
#include <vector>

namespace colonmap::io {
namespace {

// A problem with the file; caught in ReadLegacyPolyData and returned as its message.
struct Bad {
  std::string what;
};

// The value types of the legacy format as VTK's writers name them, with their size in a BINARY
// file (vtkIdType is written as a 4-byte int there, as VTK's legacy reader expects).
struct ValueType {
  const char* name;
  int vtk;
  int bytes;
  bool floating;
  bool isSigned;
};

const ValueType* FindType(const std::string& lowerName) {
  static const std::array<ValueType, 14> types{{
      {"unsigned_char", VTK_UNSIGNED_CHAR, 1, false, false},
      {"char", VTK_CHAR, 1, false, true},
      {"signed_char", VTK_SIGNED_CHAR, 1, false, true},
      {"unsigned_short", VTK_UNSIGNED_SHORT, 2, false, false},
      {"short", VTK_SHORT, 2, false, true},
      {"unsigned_int", VTK_UNSIGNED_INT, 4, false, false},
      {"int", VTK_INT, 4, false, true},
      {"unsigned_long", VTK_UNSIGNED_LONG, 8, false, false},
      {"long", VTK_LONG, 8, false, true},
      {"vtktypeuint64", VTK_TYPE_UINT64, 8, false, false},
      {"vtktypeint64", VTK_TYPE_INT64, 8, false, true},
      {"vtkidtype", VTK_ID_TYPE, 4, false, true},
      {"float", VTK_FLOAT, 4, true, true},
      {"double", VTK_DOUBLE, 8, true, true},
  }};
  for (const ValueType& t : types)
    if (lowerName == t.name) return &t;
  return nullptr;
}

// Percent-decoding of names (VTK writes a space in an array name as %20).
std::string DecodeName(const std::string& s) {
  std::string out;
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '%' && i + 2 < s.size() && std::isxdigit(static_cast<unsigned char>(s[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(s[i + 2]))) {
      out += static_cast<char>(std::stoi(s.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += s[i];
    }
  }
  return out;
}

class LegacyParser {
public:
  explicit LegacyParser(std::string bytes) : s_(std::move(bytes)) {}

  void Read(vtkPolyData* out) {
    ReadHeader();
    const std::string dataset = Keyword("DATASET");
    if (dataset != "dataset") throw Bad{"has no DATASET line after the header"};
    const std::string kind = Keyword("dataset kind");
    if (kind != "polydata") throw Bad{"is a legacy VTK " + kind + " file, not polydata"};
    vtkFieldData* attributes = nullptr;  // the point or cell data being read, once one has started
    long long attributeCount = 0;
    std::string word;
    while (NextWord(word)) {
      const std::string key = LowerCase(word);
      if (key == "points") {
        ReadPoints(out);
      } else if (key == "vertices" || key == "lines" || key == "polygons" || key == "triangle_strips") {
        if (!out->GetPoints()) throw Bad{"has " + word + " before its POINTS"};
        vtkNew<vtkCellArray> cells;
        ReadCells(word, cells, out->GetNumberOfPoints());
        if (key == "vertices") out->SetVerts(cells);
        else if (key == "lines") out->SetLines(cells);
        else if (key == "polygons") out->SetPolys(cells);
        else out->SetStrips(cells);
      } else if (key == "point_data" || key == "cell_data") {
        attributeCount = Count(word);
        const bool points = key == "point_data";
        const long long expected = points ? out->GetNumberOfPoints() : out->GetNumberOfCells();
        if (attributeCount != expected)
          throw Bad{word + " says " + std::to_string(attributeCount) + " but there are " + std::to_string(expected) +
                    (points ? " points" : " cells")};
        attributes = points ? static_cast<vtkFieldData*>(out->GetPointData()) : out->GetCellData();
      } else if (key == "field") {
        ReadField(attributes ? attributes : out->GetFieldData());
      } else if (key == "metadata") {
        SkipMetadata();
      } else if (attributes) {
        ReadAttribute(key, word, attributes, attributeCount);
      } else {
        throw Bad{"has an unknown keyword '" + Shown(word) + "'"};
      }
    }
    if (!out->GetPoints()) throw Bad{"holds no points"};
  }

private:
  const std::string s_;
  std::size_t pos_ = 0;
  bool binary_ = false;
  bool offsetsLayout_ = false;  // file version 5 and later: cells as OFFSETS and CONNECTIVITY

  static std::string Shown(const std::string& word) { return word.size() > 40 ? word.substr(0, 40) + "..." : word; }

  std::string Line() {
    const std::size_t end = s_.find('\n', pos_);
    std::string line = s_.substr(pos_, end == std::string::npos ? std::string::npos : end - pos_);
    pos_ = end == std::string::npos ? s_.size() : end + 1;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    return line;
  }

  void ReadHeader() {
    const std::string first = Line();
    const std::string tag = "# vtk DataFile Version ";
    if (first.compare(0, tag.size(), tag) != 0) throw Bad{"is not a legacy VTK file (no '# vtk DataFile Version' line)"};
    offsetsLayout_ = std::atoi(first.c_str() + tag.size()) >= 5;
    Line();  // the title
    const std::string format = LowerCase(Trim(Line()));
    if (format != "ascii" && format != "binary") throw Bad{"says neither ASCII nor BINARY on its third line"};
    binary_ = format == "binary";
  }

  bool NextWord(std::string& word) {
    while (pos_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    const std::size_t start = pos_;
    while (pos_ < s_.size() && !std::isspace(static_cast<unsigned char>(s_[pos_]))) ++pos_;
    word = s_.substr(start, pos_ - start);
    return !word.empty();
  }

  std::string Keyword(const char* what) {
    std::string word;
    if (!NextWord(word)) throw Bad{"ends where " + std::string(what) + " was expected"};
    return LowerCase(word);
  }

  std::string Name(const char* what) {
    std::string word;
    if (!NextWord(word)) throw Bad{"ends where " + std::string(what) + " was expected"};
    return DecodeName(word);
  }

  // A count in a keyword line: a whole number >= 0 that fits the file.
  long long Count(const std::string& after) {
    std::string word;
    if (!NextWord(word)) throw Bad{"ends after " + after};
    errno = 0;
    char* end = nullptr;
    const long long n = std::strtoll(word.c_str(), &end, 10);
    if (end == word.c_str() || *end != '\0' || errno == ERANGE || n < 0)
      throw Bad{"has '" + Shown(word) + "' where " + after + " needs a count"};
    return n;
  }

  const ValueType& Type(const std::string& after) {
    std::string word;
    if (!NextWord(word)) throw Bad{"ends after " + after};
    const std::string lower = LowerCase(word);
    if (lower == "bit" || lower == "string" || lower == "utf8_string" || lower == "variant")
      throw Bad{"has " + lower + " values (" + after + "), which are not read: save the surface as .vtp"};
    const ValueType* t = FindType(lower);
    if (!t) throw Bad{"has an unknown value type '" + Shown(word) + "' (" + after + ")"};
    return *t;
  }

  // In a BINARY file the values start on the line after their keyword line.
  void StartValues() {
    if (!binary_) return;
    const std::size_t end = s_.find('\n', pos_);
    pos_ = end == std::string::npos ? s_.size() : end + 1;
  }

  // The file must hold `values` values before they are allocated: a character and a separator
  // each in ASCII, their bytes in BINARY.
  void CheckRoom(double values, int bytes, const std::string& what) {
    const double room = static_cast<double>(s_.size() - pos_);
    const double needed = binary_ ? values * bytes : 2 * values - 1;
    if (values > 0 && needed > room)
      throw Bad{"is cut short: " + what + " needs " + std::to_string(static_cast<long long>(values)) +
                " values, more than the rest of the file holds"};
  }

  // The next value, of type t (`what` names it in a message).
  double Value(const ValueType& t, const std::string& what) {
    if (binary_) {
      std::uint64_t u = 0;
      for (int b = 0; b < t.bytes; ++b) u = (u << 8) | static_cast<unsigned char>(s_[pos_ + static_cast<std::size_t>(b)]);
      pos_ += static_cast<std::size_t>(t.bytes);
      if (t.floating) {
        if (t.bytes == 4) {
          const auto u32 = static_cast<std::uint32_t>(u);
          float f;
          std::memcpy(&f, &u32, 4);
          return f;
        }
        double d;
        std::memcpy(&d, &u, 8);
        return d;
      }
      if (t.isSigned && t.bytes < 8 && (u >> (8 * t.bytes - 1)) & 1u) u |= ~std::uint64_t{0} << (8 * t.bytes);
      return t.isSigned ? static_cast<double>(static_cast<std::int64_t>(u)) : static_cast<double>(u);
    }
    std::string word;
    if (!NextWord(word)) throw Bad{"is cut short in " + what};
    char* end = nullptr;
    errno = 0;
    double v = 0;
    if (t.floating) {
      v = std::strtod(word.c_str(), &end);
    } else if (t.isSigned) {
      v = static_cast<double>(std::strtoll(word.c_str(), &end, 10));
    } else {
      v = static_cast<double>(std::strtoull(word.c_str(), &end, 10));
      if (!word.empty() && word[0] == '-') errno = ERANGE;
    }
    if (end == word.c_str() || *end != '\0' || (!t.floating && errno == ERANGE))
      throw Bad{"has '" + Shown(word) + "' in " + what + ", which is not a " + t.name + " value"};
    return v;
  }

  // `tuples` x `components` values of type t into a new array of that type.
  vtkSmartPointer<vtkDataArray> Values(const ValueType& t, long long tuples, int components, const std::string& what) {
    if (components < 1 || components > 4096) throw Bad{what + " has " + std::to_string(components) + " components"};
    const double n = static_cast<double>(tuples) * components;
    CheckRoom(n, t.bytes, what);
    vtkSmartPointer<vtkDataArray> array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(t.vtk));
    array->SetNumberOfComponents(components);
    array->SetNumberOfTuples(tuples);
    for (long long i = 0; i < tuples; ++i)
      for (int c = 0; c < components; ++c) array->SetComponent(i, c, Value(t, what));
    return array;
  }

  // Integers for cell lists (counts, ids, offsets): whole numbers, as 64-bit.
  std::vector<long long> Integers(const ValueType& t, long long n, const std::string& what) {
    if (t.floating) throw Bad{what + " are " + t.name + " values, not integers"};
    CheckRoom(static_cast<double>(n), t.bytes, what);
    std::vector<long long> v(static_cast<std::size_t>(n));
    for (auto& x : v) {
      const double d = Value(t, what);
      if (!(std::abs(d) < 9.0e18)) throw Bad{what + " hold a value out of range"};
      x = static_cast<long long>(d);
    }
    return v;
  }

  void ReadPoints(vtkPolyData* out) {
    if (out->GetPoints()) throw Bad{"has two POINTS sections"};
    const long long n = Count("POINTS");
    const ValueType& t = Type("POINTS");
    StartValues();
    vtkSmartPointer<vtkDataArray> values = Values(t, n, 3, "the points");
    vtkNew<vtkPoints> points;
    points->SetData(values);
    out->SetPoints(points);
  }

  void ReadCells(const std::string& word, vtkCellArray* cells, long long points) {
    const long long first = Count(word), second = Count(word);
    std::vector<long long> offsets, connectivity;
    if (offsetsLayout_) {
      // "<KIND> <offsets> <connectivity size>", then OFFSETS <type> and CONNECTIVITY <type>.
      if (Keyword("OFFSETS") != "offsets") throw Bad{"has no OFFSETS after " + word};
      const ValueType& ot = Type(word + " offsets");
      StartValues();
      offsets = Integers(ot, first, word + " offsets");
      if (Keyword("CONNECTIVITY") != "connectivity") throw Bad{"has no CONNECTIVITY after the " + word + " offsets"};
      const ValueType& ct = Type(word + " connectivity");
      StartValues();
      connectivity = Integers(ct, second, word + " connectivity");
      if (offsets.empty()) offsets.push_back(0);
      if (offsets.front() != 0 || offsets.back() != second)
        throw Bad{"has " + word + " offsets that do not start at 0 and end at the connectivity's size"};
      for (std::size_t i = 1; i < offsets.size(); ++i)
        if (offsets[i] < offsets[i - 1]) throw Bad{"has " + word + " offsets that decrease"};
    } else {
      // "<KIND> <cells> <size>", then per cell its number of ids and the ids.
      StartValues();
      const ValueType* int32 = FindType("int");
      const std::vector<long long> list = Integers(*int32, second, word);
      offsets.reserve(static_cast<std::size_t>(std::min(first, second)) + 1);
      offsets.push_back(0);
      std::size_t at = 0;
      for (long long cell = 0; cell < first; ++cell) {
        if (at >= list.size()) throw Bad{"has fewer " + word + " than it declares (" + std::to_string(first) + ")"};
        const long long k = list[at++];
        if (k < 0 || static_cast<std::size_t>(k) > list.size() - at)
          throw Bad{"has " + word + " cell " + std::to_string(cell) + " with " + std::to_string(k) +
                    " points, more than its list holds"};
        connectivity.insert(connectivity.end(), list.begin() + static_cast<std::ptrdiff_t>(at),
                            list.begin() + static_cast<std::ptrdiff_t>(at + static_cast<std::size_t>(k)));
        at += static_cast<std::size_t>(k);
        offsets.push_back(static_cast<long long>(connectivity.size()));
      }
      if (at != list.size()) throw Bad{"has a " + word + " list longer than its " + std::to_string(first) + " cells"};
    }
    for (const long long id : connectivity)
      if (id < 0 || id >= points)
        throw Bad{"has " + word + " naming point " + std::to_string(id) + ", but there are " + std::to_string(points) +
                  " points"};
    vtkNew<vtkTypeInt64Array> o, c;
    o->SetNumberOfValues(static_cast<vtkIdType>(offsets.size()));
    for (std::size_t i = 0; i < offsets.size(); ++i) o->SetValue(static_cast<vtkIdType>(i), offsets[i]);
    c->SetNumberOfValues(static_cast<vtkIdType>(connectivity.size()));
    for (std::size_t i = 0; i < connectivity.size(); ++i) c->SetValue(static_cast<vtkIdType>(i), connectivity[i]);
    cells->SetData(o, c);
  }

  // FIELD <name> <arrays>, then per array: <name> <components> <tuples> <type> and its values.
  void ReadField(vtkFieldData* into) {
    Name("the FIELD name");
    const long long arrays = Count("FIELD");
    if (static_cast<double>(arrays) > static_cast<double>(s_.size() - pos_))
      throw Bad{"declares " + std::to_string(arrays) + " FIELD arrays, more than the file can hold"};
    for (long long a = 0; a < arrays; ++a) {
      const std::string name = Name("a FIELD array");
      if (name == "NULL_ARRAY") continue;  // VTK's mark of an array it could not write
      const long long components = Count("FIELD array '" + name + "'");
      const long long tuples = Count("FIELD array '" + name + "'");
      const ValueType& t = Type("FIELD array '" + name + "'");
      StartValues();
      if (components > 4096) throw Bad{"FIELD array '" + name + "' has " + std::to_string(components) + " components"};
      vtkSmartPointer<vtkDataArray> array =
          Values(t, tuples, static_cast<int>(components), "FIELD array '" + Shown(name) + "'");
      array->SetName(name.c_str());
      into->AddArray(array);
    }
  }

  void ReadAttribute(const std::string& key, const std::string& word, vtkFieldData* into, long long tuples) {
    int components = 0;
    vtkSmartPointer<vtkDataArray> array;
    std::string name;
    if (key == "scalars") {
      name = Name("a SCALARS name");
      const ValueType& t = Type("SCALARS '" + name + "'");
      std::string next = Keyword("LOOKUP_TABLE");
      components = 1;
      if (next != "lookup_table") {
        char* end = nullptr;
        const long c = std::strtol(next.c_str(), &end, 10);
        if (end == next.c_str() || *end != '\0' || c < 1 || c > 4)
          throw Bad{"has SCALARS '" + Shown(name) + "' with '" + Shown(next) + "' components (1 to 4)"};
        components = static_cast<int>(c);
        next = Keyword("LOOKUP_TABLE");
      }
      if (next != "lookup_table") throw Bad{"has SCALARS '" + Shown(name) + "' without LOOKUP_TABLE"};
      Name("the LOOKUP_TABLE name");
      StartValues();
      array = Values(t, tuples, components, "SCALARS '" + Shown(name) + "'");
    } else if (key == "color_scalars") {
      name = Name("a COLOR_SCALARS name");
      const long long c = Count("COLOR_SCALARS");
      if (c < 1 || c > 4) throw Bad{"has COLOR_SCALARS '" + Shown(name) + "' with " + std::to_string(c) + " components"};
      StartValues();
      // BINARY: unsigned chars; ASCII: floats in [0, 1], stored as VTK does (x 255, rounded).
      const ValueType& t = *FindType(binary_ ? "unsigned_char" : "float");
      vtkSmartPointer<vtkDataArray> read = Values(t, tuples, static_cast<int>(c), "COLOR_SCALARS '" + Shown(name) + "'");
      array = vtkSmartPointer<vtkDataArray>::Take(vtkDataArray::CreateDataArray(VTK_UNSIGNED_CHAR));
      array->SetNumberOfComponents(static_cast<int>(c));
      array->SetNumberOfTuples(tuples);
      for (long long i = 0; i < tuples; ++i)
        for (int k = 0; k < c; ++k) {
          const double v = read->GetComponent(i, k);
          array->SetComponent(i, k, binary_ ? v : std::clamp(std::floor(v * 255.0 + 0.5), 0.0, 255.0));
        }
    } else if (key == "vectors" || key == "normals" || key == "tensors" || key == "tensors6" ||
               key == "global_ids" || key == "pedigree_ids") {
      name = Name("an attribute name");
      components = key == "tensors" ? 9 : key == "tensors6" ? 6 : (key == "global_ids" || key == "pedigree_ids") ? 1 : 3;
      const ValueType& t = Type(word + " '" + name + "'");
      StartValues();
      array = Values(t, tuples, components, word + " '" + Shown(name) + "'");
    } else if (key == "texture_coordinates") {
      name = Name("a TEXTURE_COORDINATES name");
      const long long dim = Count("TEXTURE_COORDINATES");
      if (dim < 1 || dim > 3) throw Bad{"has TEXTURE_COORDINATES of dimension " + std::to_string(dim)};
      const ValueType& t = Type("TEXTURE_COORDINATES '" + name + "'");
      StartValues();
      array = Values(t, tuples, static_cast<int>(dim), "TEXTURE_COORDINATES '" + Shown(name) + "'");
    } else if (key == "lookup_table") {
      // A colour table of its own (RGBA per entry): read past, not kept.
      Name("a LOOKUP_TABLE name");
      const long long size = Count("LOOKUP_TABLE");
      StartValues();
      Values(*FindType(binary_ ? "unsigned_char" : "float"), size, 4, "LOOKUP_TABLE");
      return;
    } else {
      throw Bad{"has an unknown keyword '" + Shown(word) + "'"};
    }
    array->SetName(name.c_str());
    into->AddArray(array);
  }

  // METADATA blocks (component names, information keys) end at an empty line.
  void SkipMetadata() {
    Line();
    while (pos_ < s_.size() && !Trim(Line()).empty()) {
    }
  }
};

}  // namespace

std::string ReadLegacyPolyData(const std::string& path, vtkPolyData* output) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return "cannot be opened";
  std::ostringstream bytes;
  bytes << in.rdbuf();
  try {
    LegacyParser parser(bytes.str());
    parser.Read(output);
  } catch (const Bad& bad) {
    return bad.what;
  } catch (const std::bad_alloc&) {
    return "declares more data than can be held in memory";
  }
  return {};
}

}  // namespace colonmap::io
