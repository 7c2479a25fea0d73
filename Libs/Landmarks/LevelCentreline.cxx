#include "Landmarks/LevelCentreline.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "Landmarks/IsoLines.h"
#include "Surface/MeshTopology.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::landmarks {
namespace {

// Centroid (length weighted) of a closed vertex loop.
Eigen::RowVector3d LoopCentroid(const Eigen::MatrixXd& V, const std::vector<int>& loop) {
  Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
  double total = 0.0;
  for (std::size_t i = 0; i < loop.size(); ++i) {
    const Eigen::RowVector3d a = V.row(loop[i]), b = V.row(loop[(i + 1) % loop.size()]);
    const double len = (b - a).norm();
    sum += len * 0.5 * (a + b);
    total += len;
  }
  return total > 0 ? Eigen::RowVector3d(sum / total) : Eigen::RowVector3d(V.row(loop.front()));
}

}  // namespace

Eigen::MatrixXd SmoothAlongArc(const Eigen::MatrixXd& P, double sigma) {
  const Eigen::VectorXd a = analysis::ArcLength(P);
  const Eigen::Index n = P.rows();
  Eigen::MatrixXd out = P;
  if (sigma <= 0 || n < 3) return out;
  Eigen::Index lo = 0, hi = 0;
  for (Eigen::Index i = 1; i + 1 < n; ++i) {
    // Window shrunk symmetrically near the ends so that the curve keeps its end points.
    const double reach = std::min({3.0 * sigma, a(i) - a(0), a(n - 1) - a(i)});
    while (a(lo) < a(i) - reach) ++lo;
    while (hi + 1 < n && a(hi + 1) <= a(i) + reach) ++hi;
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    double wsum = 0.0;
    for (Eigen::Index j = lo; j <= hi; ++j) {
      const double d = a(j) - a(i);
      if (std::fabs(d) > reach) continue;
      const double w = std::exp(-0.5 * d * d / (sigma * sigma));
      sum += w * P.row(j);
      wsum += w;
    }
    out.row(i) = sum / wsum;
  }
  return out;
}

LevelCentreline ComputeLevelCentreline(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& f,
                                       const Eigen::VectorXd& levels, double smoothingMm, const Eigen::Vector3d& down) {
  const Eigen::Index n = levels.size();
  const LevelSummary sum = SummarizeLevels(V, F, f, levels, down);
  LevelCentreline out;
  Eigen::MatrixXd raw = sum.centroid;
  out.radius = sum.meanRadius;
  out.maxRadius = sum.maxRadius;
  out.lowest = sum.lowest;
  // Levels 0 and 1 are the boundary loops, which no face crosses.
  for (const std::vector<int>& loop : surface::BoundaryLoops(F)) {
    const double value = f(loop.front());
    for (Eigen::Index i = 0; i < n; ++i) {
      if (std::fabs(levels(i) - value) > 1e-9) continue;
      raw.row(i) = LoopCentroid(V, loop);
      double r = 0.0, deepest = -std::numeric_limits<double>::infinity();
      out.maxRadius(i) = 0.0;
      for (int v : loop) {
        r += (V.row(v) - raw.row(i)).norm();
        out.maxRadius(i) = std::max(out.maxRadius(i), (V.row(v) - raw.row(i)).norm());
        if (V.row(v).dot(down) > deepest) deepest = V.row(v).dot(down), out.lowest.row(i) = V.row(v);
      }
      out.radius(i) = r / static_cast<double>(loop.size());
    }
  }
  // Levels that met no face (none expected on a fine mesh) take a neighbour's values.
  for (Eigen::Index i = 0; i < n; ++i)
    if (!std::isfinite(raw(i, 0))) {
      Eigen::Index j = i;
      while (j < n && !std::isfinite(raw(j, 0))) ++j;
      const Eigen::Index from = j < n ? j : i - 1;
      if (from < 0) throw Error("colon surface: no level set of the along-colon coordinate meets the surface");
      raw.row(i) = raw.row(from);
      out.radius(i) = out.radius(from);
      out.maxRadius(i) = out.maxRadius(from);
      out.lowest.row(i) = out.lowest.row(from);
    }
  out.points = SmoothAlongArc(raw, smoothingMm);
  return out;
}

}  // namespace colonmap::landmarks
