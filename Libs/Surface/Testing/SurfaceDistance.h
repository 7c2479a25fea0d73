#pragma once
// Test helper: point-to-surface distances through vtkStaticCellLocator (VTK stays in the .cxx).
#include <Eigen/Core>

#include <vector>

namespace colonmap::surface::testing {

struct ClosestPoints {
  Eigen::VectorXd distance;     // per query point, mm
  Eigen::MatrixXd point;        // closest point on the surface
  std::vector<long> cell;       // face of the closest point
};

// Closest points on the triangle surface (V, F) of each row of Q.
ClosestPoints ClosestOnSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& Q);

// Value at fraction q (0..1) of the sorted values.
double Percentile(std::vector<double> values, double q);

}  // namespace colonmap::surface::testing
