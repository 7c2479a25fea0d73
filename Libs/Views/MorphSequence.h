#pragma once
// Supine -> prone deformation sequence (paper Fig. 12, DESIGN §2.5): after registration the two
// surfaces share the supine connectivity (registration.vtp: PronePosition per supine vertex),
// so linear interpolation of vertex positions morphs one into the other. Eigen in and out.
#include <Eigen/Core>

#include <string>
#include <vector>

namespace colonmap::views {

// The N interpolation parameters 0, 1/(N-1), ..., 1 (N >= 2; N = 1 gives {0}).
std::vector<double> MorphTimes(int frames);

// (1 - t) supine + t prone, row by row (both n x 3).
Eigen::MatrixXd MorphFrame(const Eigen::MatrixXd& supine, const Eigen::MatrixXd& prone, double t);

// The points a camera must frame so that one fixed camera shows every frame whole: the supine
// rows then the prone rows (2n x 3). A parallel projection is linear, so the projection of
// (1 - t) a + t b lies between those of a and b: whatever frames both ends frames all frames.
Eigen::MatrixXd MorphFramingPoints(const Eigen::MatrixXd& supine, const Eigen::MatrixXd& prone);

// File name of frame k, "morph_%03d" + extension (".vtp", ".png").
std::string MorphFrameName(int k, const std::string& extension);

}  // namespace colonmap::views
