#include "RealColon/MidlineAlignment.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace colonmap::realcolon {
namespace {

// Points every ~step along P (both ends kept) and their arc lengths.
Eigen::MatrixXd Resample(const Eigen::MatrixXd& P, double step, Eigen::VectorXd& arcs) {
  const Eigen::VectorXd a = analysis::ArcLength(P);
  const double L = a(a.size() - 1);
  const Eigen::Index n = std::max<Eigen::Index>(2, static_cast<Eigen::Index>(std::ceil(L / step)) + 1);
  Eigen::MatrixXd out(n, 3);
  arcs.resize(n);
  Eigen::Index j = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = L * static_cast<double>(i) / static_cast<double>(n - 1);
    while (j + 2 < a.size() && a(j + 1) < s) ++j;
    const double d = a(j + 1) - a(j);
    const double t = d > 0 ? std::clamp((s - a(j)) / d, 0.0, 1.0) : 0.0;
    out.row(i) = (1.0 - t) * P.row(j) + t * P.row(j + 1);
    arcs(i) = s;
  }
  return out;
}

}  // namespace

Eigen::VectorXd AlignAlongCurve(const Eigen::MatrixXd& reference, const Eigen::MatrixXd& curve,
                                const Eigen::VectorXd& referenceArcs, double stepMm) {
  if (reference.rows() < 2 || curve.rows() < 2) throw Error("midline alignment: each polyline needs two points");
  Eigen::VectorXd ra, ca;
  const Eigen::MatrixXd R = Resample(reference, stepMm, ra), C = Resample(curve, stepMm, ca);
  const Eigen::Index m = R.rows(), n = C.rows();
  // Accumulated cost, row by row; the step taken into each cell (0 diagonal, 1 up, 2 left).
  std::vector<unsigned char> step(static_cast<std::size_t>(m * n));
  std::vector<double> prev(static_cast<std::size_t>(n)), cur(static_cast<std::size_t>(n));
  const double inf = std::numeric_limits<double>::infinity();
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      const double d = (R.row(i) - C.row(j)).norm();
      double best = inf;
      unsigned char how = 0;
      if (i == 0 && j == 0) best = 0.0;
      if (i > 0 && j > 0 && prev[j - 1] < best) best = prev[j - 1], how = 0;
      if (i > 0 && prev[j] < best) best = prev[j], how = 1;
      if (j > 0 && cur[j - 1] < best) best = cur[j - 1], how = 2;
      cur[j] = best + d;
      step[static_cast<std::size_t>(i * n + j)] = how;
    }
    std::swap(prev, cur);
  }
  // Back-track: for each reference sample, the mean matched curve arc.
  std::vector<double> sum(static_cast<std::size_t>(m), 0.0);
  std::vector<int> count(static_cast<std::size_t>(m), 0);
  Eigen::Index i = m - 1, j = n - 1;
  while (true) {
    sum[i] += ca(j);
    ++count[i];
    if (i == 0 && j == 0) break;
    const unsigned char how = step[static_cast<std::size_t>(i * n + j)];
    if (how == 0) --i, --j;
    else if (how == 1) --i;
    else --j;
  }
  Eigen::VectorXd matched(m);
  for (Eigen::Index k = 0; k < m; ++k) matched(k) = sum[k] / count[k];
  Eigen::VectorXd out(referenceArcs.size());
  for (Eigen::Index q = 0; q < referenceArcs.size(); ++q) {
    const double s = std::clamp(referenceArcs(q), 0.0, ra(m - 1));
    Eigen::Index k = std::min<Eigen::Index>(m - 2, static_cast<Eigen::Index>(s / ra(m - 1) * (m - 1)));
    const double t = std::clamp((s - ra(k)) / (ra(k + 1) - ra(k)), 0.0, 1.0);
    out(q) = (1.0 - t) * matched(k) + t * matched(k + 1);
  }
  return out;
}

}  // namespace colonmap::realcolon
