#include "Registration/RigidResidual.h"

#include "Core/Error.h"

#include <Eigen/Geometry>
#include <cmath>

namespace colonmap::registration {

double RigidResidualRms(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to) {
  if (from.rows() != to.rows() || from.cols() != 3 || to.cols() != 3)
    throw Error("rigid residual: the points and their images must be two n x 3 arrays of the same n");
  if (from.rows() < 3) return 0.0;
  // umeyama takes points as columns.
  const Eigen::Matrix4d T = Eigen::umeyama(from.transpose(), to.transpose(), false);
  const Eigen::MatrixXd moved = (from * T.topLeftCorner<3, 3>().transpose()).rowwise() + T.topRightCorner<3, 1>().transpose();
  return std::sqrt((moved - to).rowwise().squaredNorm().mean());
}

}  // namespace colonmap::registration
