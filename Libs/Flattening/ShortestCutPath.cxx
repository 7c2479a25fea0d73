#include "Flattening/ShortestCutPath.h"

#include "Core/Error.h"

#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include <algorithm>
#include <limits>
#include <utility>

namespace colonmap::flattening {

Eigen::VectorXi ShortestCutPath(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& from,
                                const std::vector<int>& to) {
  using Graph = boost::adjacency_list<boost::vecS, boost::vecS, boost::undirectedS, boost::no_property,
                                      boost::property<boost::edge_weight_t, double>>;
  const int n = static_cast<int>(V.rows());
  // Each undirected edge once; vertex n is a source joined to every vertex of `from` at cost 0.
  std::vector<std::pair<int, int>> edges;
  edges.reserve(static_cast<std::size_t>(F.rows()) * 3 + from.size());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = F(f, c), b = F(f, (c + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  std::vector<double> weights;
  weights.reserve(edges.size() + from.size());
  for (const auto& [a, b] : edges) weights.push_back((V.row(a) - V.row(b)).norm());
  for (int v : from) {
    edges.emplace_back(v, n);
    weights.push_back(0.0);
  }
  Graph g(edges.begin(), edges.end(), weights.begin(), static_cast<std::size_t>(n) + 1);
  std::vector<double> dist(static_cast<std::size_t>(n) + 1);
  std::vector<std::size_t> pred(static_cast<std::size_t>(n) + 1);
  boost::dijkstra_shortest_paths(g, static_cast<std::size_t>(n),
                                 boost::predecessor_map(pred.data()).distance_map(dist.data()));
  int best = -1;
  for (int v : to)
    if (best < 0 || dist[v] < dist[best] || (dist[v] == dist[best] && v < best)) best = v;
  if (best < 0 || !(dist[best] < std::numeric_limits<double>::max()))
    throw Error("no path along mesh edges joins the two boundary loops");
  std::vector<int> path;
  for (std::size_t v = static_cast<std::size_t>(best); v != static_cast<std::size_t>(n); v = pred[v]) {
    path.push_back(static_cast<int>(v));
    if (pred[v] == v) throw Error("no path along mesh edges joins the two boundary loops");
  }
  std::reverse(path.begin(), path.end());
  return Eigen::Map<Eigen::VectorXi>(path.data(), static_cast<Eigen::Index>(path.size()));
}

}  // namespace colonmap::flattening
