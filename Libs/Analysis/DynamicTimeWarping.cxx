#include "Analysis/DynamicTimeWarping.h"

#include "Core/Error.h"

#include <cmath>
#include <limits>
#include <vector>

namespace colonmap::analysis {

Warping WarpSequences(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b, const WarpingOptions& o) {
  const Eigen::Index m = a.rows(), n = b.rows();
  if (m < 1 || n < 1) throw Error("sequence alignment: empty sequence");
  if (a.cols() != b.cols()) throw Error("sequence alignment: the sequences have different features");
  const double inf = std::numeric_limits<double>::infinity();
  const auto inBand = [&](Eigen::Index i, Eigen::Index j) {
    const double u = m > 1 ? static_cast<double>(i) / static_cast<double>(m - 1) : 0.0;
    const double v = n > 1 ? static_cast<double>(j) / static_cast<double>(n - 1) : 0.0;
    return std::fabs(u - v) <= o.band + 1e-12;
  };
  // Accumulated cost row by row; the step into each cell (0 diagonal, 1 from i-1, 2 from j-1).
  std::vector<unsigned char> step(static_cast<std::size_t>(m * n), 0);
  std::vector<double> prev(static_cast<std::size_t>(n), inf), cur(static_cast<std::size_t>(n), inf);
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      cur[j] = inf;
      if (!inBand(i, j) && !(i == 0 && j == 0) && !(i == m - 1 && j == n - 1)) continue;
      double best = inf;
      unsigned char how = 0;
      if (i == 0 && j == 0) best = 0.0;
      if (i > 0 && j > 0 && prev[j - 1] < best) best = prev[j - 1], how = 0;
      if (i > 0 && prev[j] + o.stepPenalty < best) best = prev[j] + o.stepPenalty, how = 1;
      if (j > 0 && cur[j - 1] + o.stepPenalty < best) best = cur[j - 1] + o.stepPenalty, how = 2;
      if (best == inf) continue;
      cur[j] = best + (a.row(i) - b.row(j)).norm();
      step[static_cast<std::size_t>(i * n + j)] = how;
    }
    std::swap(prev, cur);
  }
  Warping w;
  w.cost = prev[n - 1];
  if (!std::isfinite(w.cost)) throw Error("sequence alignment: no path within the band");
  std::vector<double> sumB(static_cast<std::size_t>(m), 0.0), sumA(static_cast<std::size_t>(n), 0.0);
  std::vector<int> countB(static_cast<std::size_t>(m), 0), countA(static_cast<std::size_t>(n), 0);
  Eigen::Index i = m - 1, j = n - 1;
  while (true) {
    sumB[i] += static_cast<double>(j), ++countB[i];
    sumA[j] += static_cast<double>(i), ++countA[j];
    ++w.length;
    if (i == 0 && j == 0) break;
    const unsigned char how = step[static_cast<std::size_t>(i * n + j)];
    if (how == 0) --i, --j;
    else if (how == 1) --i;
    else --j;
  }
  w.matchedInB.resize(m);
  w.matchedInA.resize(n);
  for (Eigen::Index k = 0; k < m; ++k) w.matchedInB(k) = sumB[k] / countB[k];
  for (Eigen::Index k = 0; k < n; ++k) w.matchedInA(k) = sumA[k] / countA[k];
  return w;
}

}  // namespace colonmap::analysis
