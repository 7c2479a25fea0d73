#include "ShortestPaths.h"

#include <boost/graph/compressed_sparse_row_graph.hpp>
#include <boost/graph/dijkstra_shortest_paths.hpp>

#include <algorithm>
#include <limits>

namespace colonmap::analysis {

namespace {

using Graph = boost::compressed_sparse_row_graph<boost::directedS, boost::no_property,
                                                 boost::property<boost::edge_weight_t, double>>;

// Both directions of every edge of g (weights: one per edge, the lengths when null), plus
// `extra` arcs; as a CSR graph, whose constructor wants the arcs sorted by source (sorted
// stably, with their weights).
Graph MakeGraph(const EdgeGraph& g, const std::vector<double>* weights, const std::vector<std::pair<int, int>>& extra,
                std::size_t vertices) {
  std::vector<std::pair<int, int>> arcs;
  std::vector<double> w;
  arcs.reserve(g.edges.size() * 2 + extra.size());
  w.reserve(arcs.capacity());
  for (std::size_t e = 0; e < g.edges.size(); ++e) {
    const double we = weights ? (*weights)[e] : g.lengths[e];
    arcs.emplace_back(g.edges[e].first, g.edges[e].second);
    w.push_back(we);
    arcs.emplace_back(g.edges[e].second, g.edges[e].first);
    w.push_back(we);
  }
  for (const auto& arc : extra) {
    arcs.push_back(arc);
    w.push_back(0.0);
  }
  std::vector<std::size_t> order(arcs.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return arcs[a] < arcs[b]; });
  std::vector<std::pair<int, int>> sortedArcs(arcs.size());
  std::vector<double> sortedW(arcs.size());
  for (std::size_t i = 0; i < order.size(); ++i) {
    sortedArcs[i] = arcs[order[i]];
    sortedW[i] = w[order[i]];
  }
  return Graph(boost::edges_are_sorted, sortedArcs.begin(), sortedArcs.end(), sortedW.begin(), vertices);
}

}  // namespace

std::vector<double> ShortestPaths(const EdgeGraph& g, const std::vector<int>& sources,
                                  const std::vector<double>* weights, std::vector<int>* predecessor) {
  // A virtual vertex n joined to every source by a zero arc: a multi-source Dijkstra with the
  // stock algorithm.
  const int n = g.vertices;
  std::vector<std::pair<int, int>> toSources;
  for (int src : sources) toSources.emplace_back(n, src);
  const Graph graph = MakeGraph(g, weights, toSources, static_cast<std::size_t>(n + 1));
  std::vector<double> dist(static_cast<std::size_t>(n + 1), std::numeric_limits<double>::infinity());
  std::vector<std::size_t> pred(static_cast<std::size_t>(n + 1));
  boost::dijkstra_shortest_paths(
      graph, static_cast<std::size_t>(n),
      boost::predecessor_map(boost::make_iterator_property_map(pred.begin(), boost::get(boost::vertex_index, graph)))
          .distance_map(boost::make_iterator_property_map(dist.begin(), boost::get(boost::vertex_index, graph))));
  if (predecessor) {
    predecessor->resize(static_cast<std::size_t>(n));
    for (int v = 0; v < n; ++v) {
      const std::size_t p = pred[static_cast<std::size_t>(v)];
      (*predecessor)[static_cast<std::size_t>(v)] = p == static_cast<std::size_t>(n) ? v : static_cast<int>(p);
    }
  }
  dist.resize(static_cast<std::size_t>(n));
  return dist;
}

struct ShortestPathGraph::Impl {
  Graph graph;
  std::size_t vertices = 0;
};

ShortestPathGraph::ShortestPathGraph(const EdgeGraph& g) : impl_(std::make_unique<Impl>()) {
  impl_->vertices = static_cast<std::size_t>(g.vertices);
  impl_->graph = MakeGraph(g, nullptr, {}, impl_->vertices);
}

ShortestPathGraph::~ShortestPathGraph() = default;

std::vector<double> ShortestPathGraph::From(int source) const {
  std::vector<double> dist(impl_->vertices, std::numeric_limits<double>::infinity());
  boost::dijkstra_shortest_paths(
      impl_->graph, static_cast<std::size_t>(source),
      boost::distance_map(boost::make_iterator_property_map(dist.begin(), boost::get(boost::vertex_index, impl_->graph))));
  return dist;
}

std::vector<int> PathTo(const std::vector<int>& predecessor, int target) {
  std::vector<int> path{target};
  while (predecessor[static_cast<std::size_t>(path.back())] != path.back())
    path.push_back(predecessor[static_cast<std::size_t>(path.back())]);
  std::reverse(path.begin(), path.end());
  return path;
}

}  // namespace colonmap::analysis
