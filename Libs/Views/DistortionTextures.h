#pragma once
// Texture tests of a registration (paper Fig. 12-13, DESIGN §2.4): a checkerboard and a pattern
// of circles defined on the supine flat rectangle, evaluated at flat points. Carried to the prone
// side through the map (each prone point takes the value at its supine image), squares and
// circles show where the registration stretches (dilatation K) and in which direction (theta).
// Eigen in and out.
#include <Eigen/Core>

namespace colonmap::views {

struct TextureOptions {
  int cellsAcross = 8;        // squares across the flat width (the loop around the colon)
  double circleRadius = 0.35;  // circle radius in cells, one circle per cell centre
};

// Per row of uv (n x 2, flat units of a rectangle of width `width`; NaN rows give NaN):
// checkerboard 0/1 by the parity of the cell (floor(u / c) + floor(v / c)), c = width / cellsAcross,
// u taken modulo the width (periodic); circles 1 within circleRadius cells of a cell centre,
// else 0.
Eigen::VectorXd CheckerboardAt(const Eigen::MatrixXd& uv, double width, const TextureOptions& options = {});
Eigen::VectorXd CirclesAt(const Eigen::MatrixXd& uv, double width, const TextureOptions& options = {});

}  // namespace colonmap::views
