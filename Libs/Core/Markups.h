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

// The positions as rows (n x 3).
inline Eigen::MatrixXd Positions(const MarkupList& m) {
  Eigen::MatrixXd P(static_cast<Eigen::Index>(m.points.size()), 3);
  for (std::size_t i = 0; i < m.points.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = m.points[i].position.transpose();
  return P;
}

}  // namespace colonmap
