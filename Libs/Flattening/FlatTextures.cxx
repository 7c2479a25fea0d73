#include "Flattening/FlatTextures.h"

#include <cmath>

namespace colonmap::flattening {

void FlatTextures(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, double width, int cellsAcross,
                  Eigen::VectorXd& checker, Eigen::VectorXd& circles) {
  const double cell = width / std::max(1, cellsAcross);
  checker.resize(F.rows());
  circles.resize(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d c = (uv.row(F(f, 0)) + uv.row(F(f, 1)) + uv.row(F(f, 2))).transpose() / 3.0;
    const double a = std::floor(c.x() / cell), b = std::floor(c.y() / cell);
    checker(f) = std::fmod(std::fabs(a + b), 2.0);
    const Eigen::Vector2d centre((a + 0.5) * cell, (b + 0.5) * cell);
    circles(f) = (c - centre).norm() < 0.35 * cell ? 1.0 : 0.0;
  }
}

}  // namespace colonmap::flattening
