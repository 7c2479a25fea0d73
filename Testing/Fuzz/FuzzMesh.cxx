// ReadMesh with its field data, on .vtp (XML PolyData: ascii, binary, appended raw or base64,
// compressed or not) and .vtk (legacy): the first byte chooses the format ('#': .vtk, anything
// else: .vtp), the whole input is the file. An Error is a correct refusal. Contract when it
// returns (MeshIO.h, TriangleMesh.h): every point finite, every triangle index in [0, points),
// every point (cell) array with one row per point (triangle) and no NaN in it (+-inf is allowed in
// an array, see CheckMesh).
// Legacy .vtk goes through our own reader (IO/LegacyVtkReader.h): VTK's trusted every count in
// the file and crashed within seconds of fuzzing.
#include "FuzzCommon.h"
#include "IO/MeshIO.h"
#include "Core/Error.h"

namespace {

void CheckArrays(const std::map<std::string, colonmap::DataArray>& arrays, Eigen::Index rows, const char* what) {
  for (const auto& [name, d] : arrays) {
    if (d.values.rows() != rows) fuzz::Violation(what);
    if (d.values.array().isNaN().any()) fuzz::Violation("an array holds NaN");
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool vtk = size > 0 && data[0] == '#';
  const std::string path = fuzz::WriteInput(data, size, vtk ? ".vtk" : ".vtp");
  try {
    colonmap::io::FieldArrays field;
    const colonmap::TriangleMesh mesh = colonmap::io::ReadMesh(path, "surface", &field);
    if (mesh.V.cols() != 3 || mesh.F.cols() != 3) fuzz::Violation("points or triangles without 3 columns");
    if (!mesh.V.allFinite()) fuzz::Violation("a point is not finite");
    if (mesh.F.size() > 0 && (mesh.F.minCoeff() < 0 || mesh.F.maxCoeff() >= mesh.V.rows()))
      fuzz::Violation("a triangle index is out of range");
    CheckArrays(mesh.pointData, mesh.V.rows(), "a point array without one row per point");
    CheckArrays(mesh.cellData, mesh.F.rows(), "a cell array without one row per triangle");
  } catch (const colonmap::Error&) {
  }
  return 0;
}
