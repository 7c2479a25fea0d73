#include "SampleSurface.h"

#include <Eigen/Geometry>

#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

namespace colonmap {
namespace analysis {

Eigen::MatrixXd SampleSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, double areaPerSample,
                              std::uint64_t seed) {
  if (!(areaPerSample > 0.0)) throw std::invalid_argument("SampleSurface: areaPerSample must be positive");
  if (V.cols() != 3 || F.cols() != 3) throw std::invalid_argument("SampleSurface: V and F need 3 columns");
  std::mt19937_64 rng(seed);
  const auto uniform = [&rng]() { return static_cast<double>(rng() >> 11) * (1.0 / 9007199254740992.0); };
  std::vector<Eigen::Vector3d> out;
  out.reserve(static_cast<std::size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)).transpose(), b = V.row(F(f, 1)).transpose(), c = V.row(F(f, 2)).transpose();
    const double area = 0.5 * (b - a).cross(c - a).norm();
    const double expected = area / areaPerSample;
    if (!(expected > 0.0)) continue;
    const long count = static_cast<long>(std::floor(expected + uniform()));
    for (long k = 0; k < count; ++k) {
      const double r1 = std::sqrt(uniform()), r2 = uniform();
      out.push_back((1.0 - r1) * a + r1 * (1.0 - r2) * b + r1 * r2 * c);
    }
  }
  Eigen::MatrixXd P(static_cast<Eigen::Index>(out.size()), 3);
  for (std::size_t i = 0; i < out.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = out[i].transpose();
  return P;
}

}  // namespace analysis
}  // namespace colonmap
