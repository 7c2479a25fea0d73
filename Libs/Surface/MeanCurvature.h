#pragma once
// Discrete differential geometry on triangle meshes (Eigen in and out): the cotangent
// Laplacian, mixed Voronoi vertex areas, vertex normals and the mean curvature
// (DESIGN §2.4; Meyer, Desbrun, Schroeder, Barr 2003). The flattening stage reuses the
// Laplacian for its harmonic maps.
#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace colonmap::surface {

// Cotangent weight matrix: L(i,j) = cot(alpha_ij) + cot(beta_ij) for every edge (i,j), with
// alpha, beta the angles opposite the edge in its (one or two) faces; L(i,i) = -sum_j L(i,j).
// So (L x)_i = sum_j w_ij (x_j - x_i). Symmetric, negative semi-definite on good meshes.
Eigen::SparseMatrix<double> CotangentLaplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Mixed Voronoi area of each vertex (mm^2): the Voronoi cell within non-obtuse triangles, and
// half / a quarter of an obtuse triangle's area at its obtuse / other corners. Sums to the
// surface area.
Eigen::VectorXd MixedVertexAreas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Area-weighted vertex normals (unit) of the right-hand face normals (counter-clockwise vertex
// order seen from where the normal points).
Eigen::MatrixXd VertexNormals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Mean curvature per vertex, in 1/length of V (mm^-1):
//   H_i = (1 / (4 A_i)) sum_j w_ij <v_i - v_j, n_i>,
// A_i the mixed area, w the cotangent weights, n_i the vertex normal. Sign: positive where the
// surface bulges towards the side its normals point to (a sphere with outward normals has
// H = +1/r). On the colon surface, whose normals point into the lumen, folds and polyps
// (bulging into the lumen) are positive and the plain tube wall is negative (about -1/(2r)).
Eigen::VectorXd MeanCurvature(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

}  // namespace colonmap::surface
