#include "MeshGraph.h"

#include <algorithm>

namespace colonmap::landmarks {

EdgeGraph MeshEdgeGraph(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  EdgeGraph g;
  g.vertices = static_cast<int>(V.rows());
  g.edges.reserve(static_cast<std::size_t>(F.rows()) * 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      g.edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(g.edges.begin(), g.edges.end());
  g.edges.erase(std::unique(g.edges.begin(), g.edges.end()), g.edges.end());
  g.lengths.resize(g.edges.size());
  for (std::size_t e = 0; e < g.edges.size(); ++e)
    g.lengths[e] = (V.row(g.edges[e].first) - V.row(g.edges[e].second)).norm();
  return g;
}

}  // namespace colonmap::landmarks
