#pragma once
// Visual checks of a conformal map (paper Fig. 7): a checkerboard and a pattern of circles
// defined in the flat rectangle and carried back to the surface as per-face values. On a
// conformal map the squares stay square and the circles round on the 3D surface (only their
// size changes). Eigen in and out.
#include <Eigen/Core>

namespace colonmap::flattening {

// uv: n x 2 flat positions, F: faces, width: rectangle width (u range), cellsAcross: squares
// across the width. checker(f) = 0/1 by the square holding face f's flat centroid; circles(f) =
// 1 when the centroid lies within 0.35 cell of a cell centre, else 0.
void FlatTextures(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, double width, int cellsAcross,
                  Eigen::VectorXd& checker, Eigen::VectorXd& circles);

}  // namespace colonmap::flattening
