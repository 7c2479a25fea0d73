#pragma once
// How far a map moves points beyond a rigid motion: the RMS distance (same units as the points)
// between the images `to` and the points `from` carried by the rotation and translation that best
// fit them (least squares, Eigen::umeyama without scaling). 0 for a rigid motion; a segment of the
// colon that bent or stretched between the scans gives more. The uncertainty model reads it per
// segment (RegistrationUncertainty.h, SegmentEvidence::deformationMm): on a wall without folds to
// match, a segment that deformed more is registered less well (issue 20).
// from, to: n x 3, row i of `to` the image of row i of `from`; n >= 3 (else 0).
#include <Eigen/Core>

namespace colonmap::registration {

double RigidResidualRms(const Eigen::MatrixXd& from, const Eigen::MatrixXd& to);

}  // namespace colonmap::registration
