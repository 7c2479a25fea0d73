#include "Landmarks/AlongColonFunction.h"

#include "Core/Error.h"
#include "Flattening/HarmonicFunction.h"
#include "Flattening/IntrinsicDelaunay.h"

#include <algorithm>
#include <string>

namespace colonmap::landmarks {

std::vector<int> GeodesicDisc(const EdgeGraph& graph, int centre, double radiusMm) {
  const std::vector<double> d = ShortestPaths(graph, {centre});
  std::vector<int> disc;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (d[i] <= radiusMm) disc.push_back(static_cast<int>(i));
  return disc;
}

Eigen::VectorXd AlongColonFunction(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& zero,
                                   const std::vector<int>& one) {
  if (zero.empty() || one.empty()) throw Error("along-colon function: an end has no vertex");
  std::vector<int> a = zero, b = one;
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  std::vector<int> common;
  std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
  if (!common.empty()) throw Error("along-colon function: the two ends of the colon overlap");
  const flattening::IntrinsicTriangulation idt = flattening::IntrinsicDelaunay(V, F, {}, false);
  const Eigen::MatrixXd w = flattening::IntrinsicCornerWeights(idt.F, idt.lengths, true);
  std::vector<int> fixed = a;
  fixed.insert(fixed.end(), b.begin(), b.end());
  Eigen::VectorXd values(static_cast<Eigen::Index>(fixed.size()));
  for (std::size_t i = 0; i < fixed.size(); ++i) values(static_cast<Eigen::Index>(i)) = i < a.size() ? 0.0 : 1.0;
  try {
    return flattening::HarmonicFunction(flattening::CotangentLaplacianFromWeights(idt.F, w, V.rows()), fixed, values);
  } catch (const Error&) {
    // Degenerate triangles (zero area, as contouring can make where the field meets the level
    // at a lattice point) give infinite cotangents: then they take none, and every corner a
    // tiny floor, so that the graph stays connected and the system positive definite.
    const Eigen::ArrayXXd finite = w.array().isFinite().select(w.array(), 0.0);
    const Eigen::MatrixXd safe = (finite + 1e-9 * std::max(1e-12, finite.abs().mean())).matrix();
    return flattening::HarmonicFunction(flattening::CotangentLaplacianFromWeights(idt.F, safe, V.rows()), fixed, values);
  }
}

Eigen::VectorXd AlongColonFunction(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int first, int second,
                                   double discMm) {
  const EdgeGraph g = MeshEdgeGraph(V, F);
  std::vector<int> zero = GeodesicDisc(g, first, discMm), one = GeodesicDisc(g, second, discMm);
  // Discs that would overlap (a very short surface) shrink to their tips.
  std::vector<int> common;
  std::set_intersection(zero.begin(), zero.end(), one.begin(), one.end(), std::back_inserter(common));
  if (!common.empty()) zero = {first}, one = {second};
  return AlongColonFunction(V, F, zero, one);
}

}  // namespace colonmap::landmarks
