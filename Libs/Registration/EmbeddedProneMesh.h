#pragma once
// The prone mesh carried inside registration.vtp (issue 23). Slicer hands a module only the file
// of the model node it was given, under a temporary name in its own folder, so nothing written
// beside registration.vtp reaches the module. registration.vtp therefore carries a lossless copy
// of registration_prone.vtp in its VTK field data, which viewers ignore and Slicer keeps through
// its load and save (RAS <-> LPS flips the points only):
//   ProneMeshPoints            n x 3 double, the prone vertices (LPS mm)
//   ProneMeshTriangles         m x 3 int, the prone triangles (the ids ProneTriangleId indexes)
//   ProneMeshPointData_<name>  n rows: each point array of registration_prone.vtp
//   ProneMeshCellData_<name>   m rows: each cell array of registration_prone.vtp
// The supine surface, its point and cell arrays are unchanged (DESIGN §2.0).
#include "Core/TriangleMesh.h"
#include "IO/MeshIO.h"

#include <optional>
#include <string>

namespace colonmap::registration {

// Adds the prone mesh to `field` (the field data of registration.vtp).
void EmbedProneMesh(const TriangleMesh& prone, io::FieldArrays* field);

// The prone mesh from registration.vtp's field data; nullopt when the file carries none (written
// before issue 23). Throws InputError naming `path` when the copy is present but inconsistent
// (a missing part, rows that do not match, triangle ids out of range, NaN).
std::optional<TriangleMesh> EmbeddedProneMesh(const io::FieldArrays& field, const std::string& path);

}  // namespace colonmap::registration
