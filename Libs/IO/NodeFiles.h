#pragma once
// Files a host such as 3D Slicer loads back as nodes (issue 23). Slicer names each output file
// parameter with a temporary name carrying the extension it will read (".vtp", ".mrk.json",
// ".nrrd", ".tsv", ...), so these write in the format the target's extension names.
#include "Core/Volume.h"

#include <string>
#include <vector>

namespace colonmap::io {

// A table for Slicer's table node: a header row and rows of text cells.
struct TextTable {
  std::vector<std::string> columns;
  std::vector<std::vector<std::string>> rows;
};

// ".csv": comma-separated, cells quoted where needed (RFC 4180); anything else (".tsv", ".txt"):
// tab-separated, tabs and line breaks in cells replaced by spaces.
void WriteTable(const TextTable& table, const std::string& path, const std::string& what);

enum class NodeFileKind { Model, Markups, Table };

// Writes the file `source` (written by us) again as `target`: a byte copy when both name the same
// format, else read by our reader and written by our writer in the target's format (.vtp <-> .vtk,
// .mrk.json <-> .fcsv, .tsv <-> .csv). Throws colonmap::Error naming `what`.
void CopyNodeFile(NodeFileKind kind, const std::string& source, const std::string& target, const std::string& what);

// The same for an image of voxel type T (short, unsigned char, float): NRRD, NIfTI, MetaImage.
template <typename T>
void CopyImageFile(const std::string& source, const std::string& target, const std::string& what);

}  // namespace colonmap::io
