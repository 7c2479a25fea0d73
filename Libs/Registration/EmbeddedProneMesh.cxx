#include "Registration/EmbeddedProneMesh.h"

#include "Core/Error.h"

namespace colonmap::registration {
namespace {

const std::string kPoints = "ProneMeshPoints", kTriangles = "ProneMeshTriangles", kPointPrefix = "ProneMeshPointData_",
                  kCellPrefix = "ProneMeshCellData_";

bool StartsWith(const std::string& s, const std::string& prefix) { return s.compare(0, prefix.size(), prefix) == 0; }

}  // namespace

void EmbedProneMesh(const TriangleMesh& prone, io::FieldArrays* field) {
  (*field)[kPoints] = DataArray{prone.V, false};
  (*field)[kTriangles] = DataArray{prone.F.cast<double>(), true};
  for (const auto& [name, d] : prone.pointData) (*field)[kPointPrefix + name] = d;
  for (const auto& [name, d] : prone.cellData) (*field)[kCellPrefix + name] = d;
}

std::optional<TriangleMesh> EmbeddedProneMesh(const io::FieldArrays& field, const std::string& path) {
  const std::string what = "registration (the prone mesh it carries)";
  const auto points = field.find(kPoints), triangles = field.find(kTriangles);
  if (points == field.end() && triangles == field.end()) return std::nullopt;
  if (points == field.end() || triangles == field.end())
    throw InputError(what, path, "has field data " + (points == field.end() ? kTriangles : kPoints) + " without " +
                                     (points == field.end() ? kPoints : kTriangles));
  if (points->second.values.cols() != 3 || triangles->second.values.cols() != 3 || triangles->second.values.rows() == 0)
    throw InputError(what, path, kPoints + " and " + kTriangles + " must have 3 components and hold triangles");
  TriangleMesh prone;
  prone.V = points->second.values;
  prone.F = triangles->second.values.cast<int>();
  for (const auto& [name, d] : field) {
    const bool isPoint = StartsWith(name, kPointPrefix), isCell = StartsWith(name, kCellPrefix);
    if (!isPoint && !isCell) continue;
    const Eigen::Index rows = isPoint ? prone.V.rows() : prone.F.rows();
    if (d.values.rows() != rows)
      throw InputError(what, path, "field data " + name + " has " + std::to_string(d.values.rows()) + " rows, expected " +
                                       std::to_string(rows));
    (isPoint ? prone.pointData : prone.cellData)[name.substr((isPoint ? kPointPrefix : kCellPrefix).size())] = d;
  }
  io::CheckMesh(prone, path, what);
  return prone;
}

}  // namespace colonmap::registration
