#include "IO/NodeFiles.h"
#include "IO/FileNames.h"

#include "Core/Error.h"
#include "IO/ImageIO.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"

#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace colonmap::io {
namespace {

// Extension as our readers and writers see it, double extensions kept (".mrk.json", ".nii.gz").
std::string Format(const std::string& path) {
  const std::string name = LowerCase(fs::path(path).filename().string());
  for (const std::string two : {".mrk.json", ".nii.gz"})
    if (name.size() > two.size() && name.compare(name.size() - two.size(), two.size(), two) == 0) return two;
  return fs::path(name).extension().string();
}

void CopyBytes(const std::string& source, const std::string& target, const std::string& what) {
  std::error_code ec;
  if (!fs::is_regular_file(source, ec)) throw InputError(what, source, "was not written");
  fs::copy_file(source, target, fs::copy_options::overwrite_existing, ec);
  if (ec) throw InputError(what, target, "cannot be written (" + ec.message() + ")");
}

bool IsCsv(const std::string& path) { return Format(path) == ".csv"; }

std::string CsvCell(const std::string& cell) {
  if (cell.find_first_of(",\"\r\n") == std::string::npos) return cell;
  std::string q = "\"";
  for (const char c : cell) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

// Rows of a .tsv or .csv file we wrote (no quoted line breaks).
TextTable ReadTable(const std::string& path, const std::string& what) {
  std::ifstream in(path);
  if (!in) throw InputError(what, path, "cannot be read");
  const bool csv = IsCsv(path);
  TextTable t;
  for (std::string line; std::getline(in, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::vector<std::string> cells;
    std::string cell;
    bool quoted = false;
    for (std::size_t i = 0; i < line.size(); ++i) {
      const char c = line[i];
      if (csv && quoted) {
        if (c == '"' && i + 1 < line.size() && line[i + 1] == '"') cell += '"', ++i;
        else if (c == '"') quoted = false;
        else cell += c;
      } else if (csv && c == '"') {
        quoted = true;
      } else if (c == (csv ? ',' : '\t')) {
        cells.push_back(cell);
        cell.clear();
      } else {
        cell += c;
      }
    }
    cells.push_back(cell);
    if (t.columns.empty()) t.columns = cells;
    else t.rows.push_back(cells);
  }
  return t;
}

}  // namespace

void WriteTable(const TextTable& table, const std::string& path, const std::string& what) {
  const bool csv = IsCsv(path);
  std::ostringstream out;
  const auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t i = 0; i < cells.size(); ++i) {
      std::string c = cells[i];
      if (csv) c = CsvCell(c);
      else
        for (auto& ch : c)
          if (ch == '\t' || ch == '\n' || ch == '\r') ch = ' ';
      out << (i ? (csv ? "," : "\t") : "") << c;
    }
    out << "\n";
  };
  line(table.columns);
  for (const auto& r : table.rows) line(r);
  WriteText(out.str(), path, what);
}

void CopyNodeFile(NodeFileKind kind, const std::string& source, const std::string& target, const std::string& what) {
  if (Format(source) == Format(target)) return CopyBytes(source, target, what);
  switch (kind) {
    case NodeFileKind::Model: {
      FieldArrays field;
      const TriangleMesh mesh = ReadMesh(source, what, &field);
      return WriteMesh(mesh, target, what, field);
    }
    case NodeFileKind::Markups:
      return WriteMarkups(ReadMarkups(source, what), target, what);
    case NodeFileKind::Table:
      return WriteTable(ReadTable(source, what), target, what);
  }
}

template <typename T>
void CopyImageFile(const std::string& source, const std::string& target, const std::string& what) {
  if (Format(source) == Format(target)) return CopyBytes(source, target, what);
  WriteImage(ReadImage<T>(source, what), target, what);
}

template void CopyImageFile<short>(const std::string&, const std::string&, const std::string&);
template void CopyImageFile<unsigned char>(const std::string&, const std::string&, const std::string&);
template void CopyImageFile<float>(const std::string&, const std::string&, const std::string&);

}  // namespace colonmap::io
