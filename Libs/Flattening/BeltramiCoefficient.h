#pragma once
// Distortion of a map from a surface to the plane, per face (DESIGN §2.3, §3.3): the Beltrami
// coefficient mu = f_zbar / f_z of the piecewise-linear map in each triangle's own orthonormal
// frame (e1 along the first edge, e2 = n x e1, n the right-hand normal), the signed area of the
// image (flipped triangles: <= 0) and the area ratio. Eigen in and out.
#include <Eigen/Core>

#include <complex>

namespace colonmap::flattening {

// mu per face of the map V (m x 3 surface) -> uv (same vertex indexing, n x 2).
// |mu| = 0 for a conformal (similarity) face, < 1 orientation-preserving, > 1 flipped.
Eigen::VectorXcd BeltramiCoefficient(const Eigen::MatrixXd& V, const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F);

// Signed area of each face in the plane (positive = counter-clockwise, same orientation as the
// surface seen from its normal side).
Eigen::VectorXd SignedFlatAreas(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F);

// Area of each face of the surface V (m x 3).
Eigen::VectorXd SurfaceFaceAreas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Summary of the distortion of one map.
struct DistortionStats {
  long faces = 0;
  long flipped = 0;                          // signed flat area <= 0
  double muMean = 0, muP99 = 0, muMax = 0;   // of |mu|
  // Area ratio per face: (flat area / total flat area) / (surface area / total surface area).
  double areaRatioMin = 0, areaRatioP01 = 0, areaRatioMedian = 0, areaRatioP99 = 0, areaRatioMax = 0;
  double logAreaRatioStd = 0;                // area-weighted standard deviation of log ratio
};
DistortionStats SummarizeDistortion(const Eigen::MatrixXd& V, const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F,
                                    const Eigen::VectorXcd& mu);

// The q-quantile (0..1) of values (nearest rank on a sorted copy; 0 for an empty vector).
double Quantile(const Eigen::VectorXd& values, double q);

}  // namespace colonmap::flattening
