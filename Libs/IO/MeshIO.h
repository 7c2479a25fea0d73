#pragma once
// Surface and polyline files <-> TriangleMesh / PolylineSet, through VTK readers and writers.
// Read: .vtp, .vtk (legacy polydata), .stl; polygons are triangulated. Write: .vtp (binary,
// compressed) or .vtk. Named point/cell arrays are kept (DESIGN §3.3).
#include "Core/Polyline.h"
#include "Core/TriangleMesh.h"

#include <string>

namespace colonmap::io {

TriangleMesh ReadMesh(const std::string& path, const std::string& what);
void WriteMesh(const TriangleMesh& mesh, const std::string& path, const std::string& what);

PolylineSet ReadPolylines(const std::string& path, const std::string& what);
// Line names go to a string cell array "Name" and to the per-line "Closed" flag.
void WritePolylines(const PolylineSet& lines, const std::string& path, const std::string& what);

}  // namespace colonmap::io
