#include "Registration/FoldGraphCut.h"

#include "Core/Error.h"

// Boost.Graph's edge iterators trip GCC's -Wmaybe-uninitialized (false positives in Boost).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>

namespace colonmap::registration {

namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using Graph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS,
    boost::property<boost::vertex_index_t, long,
                    boost::property<boost::vertex_color_t, boost::default_color_type,
                                    boost::property<boost::vertex_distance_t, long,
                                                    boost::property<boost::vertex_predecessor_t, Traits::edge_descriptor>>>>,
    boost::property<boost::edge_capacity_t, long,
                    boost::property<boost::edge_residual_capacity_t, long, boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;

// An edge a -> b of capacity c with its reverse b -> a of capacity r (BK needs both).
void AddPair(Graph& g, long a, long b, long c, long r) {
  auto capacity = boost::get(boost::edge_capacity, g);
  auto reverse = boost::get(boost::edge_reverse, g);
  const auto e = boost::add_edge(a, b, g).first, f = boost::add_edge(b, a, g).first;
  capacity[e] = c;
  capacity[f] = r;
  reverse[e] = f;
  reverse[f] = e;
}

}  // namespace

FoldMask SegmentFoldsByGraphCut(const std::vector<float>& image, int rows, int cols, bool periodic, const GraphCutOptions& o) {
  if (rows <= 0 || cols <= 0 || image.size() != static_cast<std::size_t>(rows) * cols)
    throw Error("curvature image: size does not match its rows and columns");
  const long n = static_cast<long>(image.size());
  FoldMask out;
  // Robust normalisation: the folds are the bright tail, so median and MAD describe the wall.
  std::vector<float> v = image;
  std::nth_element(v.begin(), v.begin() + n / 2, v.end());
  const float median = v[n / 2];
  for (float& x : v) x = std::fabs(x - median);
  std::nth_element(v.begin(), v.begin() + n / 2, v.end());
  const float mad = std::max(1e-9f, 1.4826f * v[n / 2]);
  out.z.resize(n);
  for (long p = 0; p < n; ++p) out.z[p] = (image[p] - median) / mad;
  v = out.z;
  const long q = std::clamp<long>(static_cast<long>(o.quantile * (n - 1)), 0, n - 1);
  std::nth_element(v.begin(), v.begin() + q, v.end());
  out.threshold = v[q];

  constexpr double kScale = 1000.0;  // integer capacities: exact, deterministic max-flow
  Graph g(n + 2);
  const long source = n, sink = n + 1;  // source side = fold
  for (long p = 0; p < n; ++p) {
    const double d = std::clamp(out.z[p] - out.threshold, -o.clip, o.clip);
    // Cutting source -> p labels p background (cost d when above t); p -> sink labels it fold.
    if (d > 0) AddPair(g, source, p, std::lround(kScale * d), 0);
    else if (d < 0) AddPair(g, p, sink, std::lround(-kScale * d), 0);
  }
  const long w = std::lround(kScale * o.smoothness);
  if (w > 0)
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < cols; ++i) {
        const long p = static_cast<long>(j) * cols + i;
        if (i + 1 < cols) AddPair(g, p, p + 1, w, w);
        else if (periodic && cols > 2) AddPair(g, p, static_cast<long>(j) * cols, w, w);
        if (j + 1 < rows) AddPair(g, p, p + cols, w, w);
      }
  out.cutCost = boost::boykov_kolmogorov_max_flow(g, source, sink);
  // After the flow, vertices still reachable from the source (its tree) are black: the fold side.
  const auto color = boost::get(boost::vertex_color, g);
  out.fold.assign(n, 0);
  for (long p = 0; p < n; ++p) out.fold[p] = color[p] == boost::color_traits<boost::default_color_type>::black();
  return out;
}

}  // namespace colonmap::registration
