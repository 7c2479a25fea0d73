#include "Surface/SignedVolume.h"

#include <Eigen/Geometry>

namespace colonmap::surface {

double SignedVolume(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double v = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    v += a.dot(b.cross(c));
  }
  return v / 6.0;
}

}  // namespace colonmap::surface
