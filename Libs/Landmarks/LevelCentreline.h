#pragma once
// A centreline from the level sets of an along-colon function (issue 17's material coordinates
// and issue 19's centreline): each level set is one loop around the tube (AlongColonFunction.h),
// and the sequence of their centroids runs along the middle of the lumen through bends tighter
// than the lumen and past touching loops, where centroids of geodesic-distance bins cut corners
// or mix two loops. libigl style: Eigen in and out.
#include <Eigen/Core>

namespace colonmap::landmarks {

// The centreline of one embedding of a tube (V, F with the along-colon function f per vertex;
// a tube opened at two level sets has them as its boundary loops): the centroids of the level sets at `levels` (0 and 1: the boundary
// loops), smoothed along the sequence by a Gaussian of smoothingMm. The same construction on
// the supine and the prone tube, so sample i is the same material loop in both. Optionally the
// mean loop radius and the lowest point along `down` of each level set.
struct LevelCentreline {
  Eigen::MatrixXd points;    // levels x 3
  Eigen::VectorXd radius;    // mean distance of the loop from its (raw) centroid
  Eigen::VectorXd maxRadius; // largest distance of a loop point from it
  Eigen::MatrixXd lowest;    // levels x 3
};
LevelCentreline ComputeLevelCentreline(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& f,
                                       const Eigen::VectorXd& levels, double smoothingMm,
                                       const Eigen::Vector3d& down = Eigen::Vector3d(0, 1, 0));


// Gaussian smoothing of a sampled curve in its own arc length (sigma mm); the end points stay.
Eigen::MatrixXd SmoothAlongArc(const Eigen::MatrixXd& P, double sigma);

}  // namespace colonmap::landmarks
