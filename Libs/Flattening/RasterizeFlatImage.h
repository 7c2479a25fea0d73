#pragma once
// Rasterising a per-vertex quantity of a flattened mesh into an image (DESIGN §2.4): every
// pixel centre of the rectangle [0, width] x [0, height] takes the barycentric interpolation of
// the values of the flat triangle that contains it. Eigen and Core in and out.
#include "Core/Volume.h"

#include <Eigen/Core>

namespace colonmap::flattening {

struct RasterInfo {
  long covered = 0;    // pixels whose centre lies in a flat triangle
  long filled = 0;     // pixels outside every triangle (rounding at the rectangle's rim, or
                       // gaps of a non-rectangular map), set to the mean of their filled neighbours
};

// uv: n x 2 flat positions, F: faces, values: n per-vertex values. Image nx x ny x 1, pixel
// (i, j) centred at ((i + 0.5) width / nx, (j + 0.5) height / ny); spacing (width / nx,
// height / ny, 1), origin at the first pixel centre, identity direction. Where triangles
// overlap (only on shared edges for a valid map) the lowest face index wins: deterministic.
// period > 0: the map is periodic in u with that period (a periodic-cut flattening, see
// ConformalFlattening.h): each face is also drawn shifted by -period and +period, so the
// rectangle is covered across the wiggly cut.
Volume<float> RasterizeFlatImage(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, const Eigen::VectorXd& values,
                                 double width, double height, int nx, int ny, RasterInfo* info = nullptr,
                                 double period = 0.0);

}  // namespace colonmap::flattening
