#pragma once
// Signed volume of a closed triangle surface, libigl style: positive when the faces run
// counter-clockwise seen from outside (normals outward), negative when they point inward.
#include <Eigen/Core>

namespace colonmap::surface {

// V: n x 3 vertices, F: m x 3 faces of a closed surface. Returns the enclosed volume (mm^3) with
// the sign of its orientation.
double SignedVolume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace colonmap::surface
