#pragma once
// A list of labelled points (Slicer markups). Positions are always LPS mm in memory;
// readers convert from the file's coordinate system.
#include <Eigen/Core>
#include <string>
#include <vector>

namespace colonmap {

struct ControlPoint {
  std::string label;
  Eigen::Vector3d position{0.0, 0.0, 0.0};  // LPS mm
  std::string description;
};

struct MarkupList {
  std::string type = "Fiducial";  // Fiducial, Curve, ClosedCurve, Line
  std::string name;
  std::vector<ControlPoint> points;
};

}  // namespace colonmap
