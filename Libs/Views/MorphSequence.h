#pragma once
// Supine -> prone deformation sequence (paper Fig. 12, DESIGN §2.5): after registration the two
// surfaces share the supine connectivity (registration.vtp: PronePosition per supine vertex),
// so linear interpolation of vertex positions morphs one into the other. Eigen in and out.
#include <Eigen/Core>

#include <vector>

namespace colonmap::views {

// The N interpolation parameters 0, 1/(N-1), ..., 1 (N >= 2; N = 1 gives {0}).
std::vector<double> MorphTimes(int frames);

// (1 - t) supine + t prone, row by row (both n x 3).
Eigen::MatrixXd MorphFrame(const Eigen::MatrixXd& supine, const Eigen::MatrixXd& prone, double t);

}  // namespace colonmap::views
