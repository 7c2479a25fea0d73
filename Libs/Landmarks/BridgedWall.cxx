#include "Landmarks/BridgedWall.h"

#include <algorithm>
#include <cmath>

namespace colonmap::landmarks {

std::vector<bool> OnBridgedWall(const TriangleMesh& mesh, const Eigen::VectorXd& alongColon,
                                const Eigen::MatrixXd& points, int bins) {
  std::vector<bool> out(static_cast<std::size_t>(points.rows()), false);
  const auto it = mesh.pointData.find("Virtual");
  if (it == mesh.pointData.end() || it->second.values.rows() != mesh.V.rows() || alongColon.size() != mesh.V.rows())
    return out;
  const Eigen::VectorXd marks = it->second.values.col(0);
  if (!(marks.maxCoeff() > 0.5)) return out;
  const auto bin = [&](double f) { return std::clamp(static_cast<int>(std::floor(f * bins)), 0, bins - 1); };
  // Share of virtual vertices per level-set bin.
  std::vector<double> virtualCount(static_cast<std::size_t>(bins), 0.0), count(static_cast<std::size_t>(bins), 0.0);
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const std::size_t b = static_cast<std::size_t>(bin(alongColon(v)));
    count[b] += 1.0;
    virtualCount[b] += marks(v) > 0.5 ? 1.0 : 0.0;
  }
  for (Eigen::Index q = 0; q < points.rows(); ++q) {
    Eigen::Index nearest = 0;
    (mesh.V.rowwise() - points.row(q)).rowwise().squaredNorm().minCoeff(&nearest);
    const std::size_t b = static_cast<std::size_t>(bin(alongColon(nearest)));
    out[static_cast<std::size_t>(q)] = count[b] > 0 && virtualCount[b] >= 0.5 * count[b];
  }
  return out;
}

}  // namespace colonmap::landmarks
