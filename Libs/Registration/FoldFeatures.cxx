#include "Registration/FoldFeatures.h"

#include "Core/Error.h"
#include "Registration/FlatLocator.h"
#include "Surface/MeanCurvature.h"

#include <Eigen/Eigenvalues>
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/connected_components.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>

namespace colonmap::registration {

Eigen::VectorXi GlueCutCopies(const Eigen::MatrixXd& position, int& count) {
  std::map<std::array<double, 3>, int> seen;
  Eigen::VectorXi id(position.rows());
  count = 0;
  for (Eigen::Index i = 0; i < position.rows(); ++i) {
    const auto [it, fresh] = seen.emplace(std::array<double, 3>{position(i, 0), position(i, 1), position(i, 2)}, count);
    if (fresh) ++count;
    id(i) = it->second;
  }
  return id;
}

std::vector<FoldFeature> DetectFolds(const FlatSegment& flat, const Eigen::VectorXd& H, const FoldOptions& options) {
  const Eigen::Index n = flat.uv.rows();
  if (H.size() != n) throw Error("MeanCurvature must have one value per flat vertex");
  if (n == 0 || flat.F.rows() == 0) return {};
  std::vector<double> sorted(H.data(), H.data() + n);
  std::sort(sorted.begin(), sorted.end());
  const double threshold = sorted[std::min<std::size_t>(n - 1, static_cast<std::size_t>(options.percentile * (n - 1)))];

  // Components of above-threshold vertices, glued across the cut (Boost.Graph).
  int glued = 0;
  const Eigen::VectorXi g = GlueCutCopies(flat.position, glued);
  std::vector<char> high(glued, 0);
  for (Eigen::Index i = 0; i < n; ++i)
    if (H(i) > threshold) high[g(i)] = 1;
  boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS> graph(glued);
  for (Eigen::Index f = 0; f < flat.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = g(flat.F(f, k)), b = g(flat.F(f, (k + 1) % 3));
      if (a < b && high[a] && high[b]) boost::add_edge(a, b, graph);  // each undirected edge from one side
    }
  std::vector<int> component(glued);
  const int nc = boost::connected_components(graph, component.data());

  // Per component: the cut mesh's vertices (both copies at the cut carry half the area each).
  const Eigen::VectorXd area = surface::MixedVertexAreas(flat.position, flat.F);
  std::vector<std::vector<Eigen::Index>> members(nc);
  for (Eigen::Index i = 0; i < n; ++i)
    if (high[g(i)]) members[component[g(i)]].push_back(i);
  const FlatTriangleLocator locator(flat.uv, flat.F, flat.period);
  std::vector<FoldFeature> folds;
  for (const auto& m : members) {
    if (m.empty()) continue;
    double a = 0;
    for (Eigen::Index i : m) a += area(i);
    if (a < options.minAreaMm2) continue;
    // u unwrapped next to the first member, so that a fold across the cut stays in one piece.
    const double u0 = flat.uv(m.front(), 0);
    auto unwrapped = [&](Eigen::Index i) {
      Eigen::Vector2d p = flat.uv.row(i).transpose();
      if (flat.period > 0) p.x() -= flat.period * std::round((p.x() - u0) / flat.period);
      return p;
    };
    Eigen::Vector2d c(0, 0);
    double h = 0;
    for (Eigen::Index i : m) {
      c += area(i) * unwrapped(i);
      h += area(i) * H(i);
    }
    c /= a;
    Eigen::Matrix2d cov = Eigen::Matrix2d::Zero();
    for (Eigen::Index i : m) {
      const Eigen::Vector2d d = unwrapped(i) - c;
      cov += area(i) * d * d.transpose();
    }
    cov /= a;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(cov);
    FoldFeature f;
    f.axis = eig.eigenvectors().col(1);
    if (f.axis.x() < 0 || (f.axis.x() == 0 && f.axis.y() < 0)) f.axis = -f.axis;
    f.orientation = std::atan2(f.axis.y(), f.axis.x());
    f.halfLength = std::sqrt(3.0 * std::max(0.0, eig.eigenvalues()(1)));  // uniform segment of that variance
    if (flat.period > 0) c.x() -= flat.period * std::floor(c.x() / flat.period);
    f.centroid = c;
    f.ends[0] = c - f.halfLength * f.axis;
    f.ends[1] = c + f.halfLength * f.axis;
    f.areaMm2 = a;
    f.meanCurvature = h / a;
    f.vertices = static_cast<int>(m.size());
    const FlatHit hit = locator.Locate(c);
    for (int k = 0; k < 3; ++k) f.position += hit.bary(k) * flat.position.row(flat.F(hit.face, k)).transpose();
    folds.push_back(f);
  }
  std::sort(folds.begin(), folds.end(), [](const FoldFeature& x, const FoldFeature& y) {
    return x.centroid.y() != y.centroid.y() ? x.centroid.y() < y.centroid.y() : x.centroid.x() < y.centroid.x();
  });
  return folds;
}

}  // namespace colonmap::registration
