#pragma once
// Closest points on a triangle surface (exact closest point on its triangles, VTK's static cell
// locator; VTK stays in the .cxx), for comparing a reconstructed surface with a true one.
#include <Eigen/Core>
#include <vector>

namespace colonmap::surface {

struct ClosestPoints {
  Eigen::VectorXd distance;  // per query point, mm
  Eigen::MatrixXd point;     // closest point on the surface
  std::vector<long> cell;    // face of the closest point
};

// Closest points on the triangle surface (V, F) of each row of Q.
ClosestPoints ClosestOnSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& Q);

}  // namespace colonmap::surface
