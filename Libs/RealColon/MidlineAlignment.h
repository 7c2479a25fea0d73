#pragma once
// Carrying points given along one midline (an atlas's, with its landmarks) onto another curve
// through the same tube (our level-set centreline), in order: a nearest-point projection can
// jump to another loop where the colon touches itself or bends back, an ordered alignment
// cannot. Dynamic time warping (Analysis/DynamicTimeWarping.h) of the two polylines resampled at
// stepMm, cost the point distance, libigl style.
#include <Eigen/Core>

namespace colonmap::realcolon {

// reference, curve: polylines (m x 3, n x 3) running the same way. Returns, for every arc length
// in `referenceArcs` (along `reference`), the arc length along `curve` matched to it.
Eigen::VectorXd AlignAlongCurve(const Eigen::MatrixXd& reference, const Eigen::MatrixXd& curve,
                                const Eigen::VectorXd& referenceArcs, double stepMm = 2.0);

}  // namespace colonmap::realcolon
