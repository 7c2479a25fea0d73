#pragma once
// Surface and polyline files <-> TriangleMesh / PolylineSet, through VTK readers and writers.
// Read: .vtp, .vtk (legacy polydata), .stl; polygons are triangulated. Write: .vtp (binary,
// compressed) or .vtk. Named point/cell arrays are kept (DESIGN §3.3).
#include "Core/Polyline.h"
#include "Core/TriangleMesh.h"

#include <map>
#include <string>

namespace colonmap::io {

// Field data: whole-file numeric arrays of any length (VTK field data), e.g. a second mesh
// carried inside registration.vtp (issue 23). String arrays (Slicer's SPACE) are not read.
using FieldArrays = std::map<std::string, DataArray>;

TriangleMesh ReadMesh(const std::string& path, const std::string& what);
// The same, and the file's numeric field data into *fieldData (when not null).
TriangleMesh ReadMesh(const std::string& path, const std::string& what, FieldArrays* fieldData);
void WriteMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what);
void WriteMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what, const FieldArrays& fieldData);
// What every reader checks at the door: finite points, triangle ids in range, no NaN in an array;
// throws InputError naming `what` and `path`. For meshes assembled from other data than a file's
// own points and cells (e.g. one carried in field data).
void CheckMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what);

PolylineSet ReadPolylines(const std::string& path, const std::string& what);
// Line names go to a string cell array "Name" and to the per-line "Closed" flag.
void WritePolylines(const PolylineSet& lines, const std::string& path, const std::string& what);

}  // namespace colonmap::io
