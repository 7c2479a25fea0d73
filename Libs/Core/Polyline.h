#pragma once
// Named open or closed polylines (centerlines, taeniae, cut loops) with per-point arrays.
#include "Core/TriangleMesh.h"

#include <vector>

namespace colonmap {

struct Polyline {
  std::string name;
  Eigen::MatrixXd points;  // k x 3, LPS mm
  bool closed = false;
};

struct PolylineSet {
  std::vector<Polyline> lines;
  // Per-point arrays over all lines' points concatenated in order.
  std::map<std::string, DataArray> pointData;
  // Per-line arrays, one row per line.
  std::map<std::string, DataArray> cellData;
};

}  // namespace colonmap
