#pragma once
// Our reader of legacy VTK polydata files (.vtk, "# vtk DataFile Version x.x", ASCII or BINARY),
// used instead of VTK's vtkPolyDataReader, which trusts every count in the file and goes on after
// its own errors: a malformed .vtk crashed it within seconds of fuzzing (docs/fuzzing.md).
//
// Reads what VTK's legacy writers write for polydata: POINTS; VERTICES, LINES, POLYGONS and
// TRIANGLE_STRIPS in both cell layouts (file versions up to 4.2: "n size" then each cell's count
// and ids; 5.x: OFFSETS and CONNECTIVITY arrays); FIELD data of the dataset; POINT_DATA and
// CELL_DATA with SCALARS (and their LOOKUP_TABLE name), COLOR_SCALARS, VECTORS, NORMALS,
// TEXTURE_COORDINATES, TENSORS, GLOBAL_IDS, PEDIGREE_IDS and FIELD arrays; METADATA blocks are
// skipped. Every count is checked against what the file holds before anything is allocated, every
// value must parse, cell ids must lie in the points. Not read (refused with a clear problem): bit
// and string arrays, separate LOOKUP_TABLE colour tables, other dataset kinds.
#include <string>

class vtkPolyData;

namespace colonmap::io {

// Reads `path` into `output`; returns "" on success, else the problem in a few words (for the
// one-line error that names the user's file), and `output` is then to be discarded.
std::string ReadLegacyPolyData(const std::string& path, vtkPolyData* output);

}  // namespace colonmap::io
