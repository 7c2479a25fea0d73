#pragma once
// A triangle mesh in LPS millimetres with named per-point and per-cell arrays, libigl style
// (Eigen matrices in and out). The array names are part of the file interface (DESIGN §3.3).
#include <Eigen/Core>
#include <map>
#include <string>

namespace colonmap {

struct DataArray {
  Eigen::MatrixXd values;  // one row per point (or cell), one column per component
  bool integer = false;    // written as an integer array (e.g. SegmentId)
};

struct TriangleMesh {
  Eigen::MatrixXd V;  // n x 3 vertex positions
  Eigen::MatrixXi F;  // m x 3 vertex indices, counter-clockwise seen from where normals point
  std::map<std::string, DataArray> pointData;
  std::map<std::string, DataArray> cellData;

  Eigen::Index NumberOfPoints() const { return V.rows(); }
  Eigen::Index NumberOfFaces() const { return F.rows(); }
};

}  // namespace colonmap
