#pragma once
// A low-pass filter of per-vertex values on a triangle mesh (Eigen in and out): each pass
// replaces a vertex's value by the mean of its own and its one-ring's; the reach grows about as
// the square root of the passes times the edge length. Used where a per-vertex quantity (the
// mean curvature) is noisy on the scale of a few triangles.
#include <Eigen/Core>

namespace colonmap::surface {

// values: n x k, one column per quantity, over the vertices 0..n-1 of the faces F. The ring of a
// vertex is the vertex after it in each of its faces (on a closed mesh every neighbour once; a
// boundary vertex misses one). passes <= 0 returns the values.
Eigen::MatrixXd RingAverage(const Eigen::MatrixXi& F, const Eigen::MatrixXd& values, int passes);

}  // namespace colonmap::surface
