#include "Surface/RingAverage.h"

#include <vector>

namespace colonmap::surface {

Eigen::MatrixXd RingAverage(const Eigen::MatrixXi& F, const Eigen::MatrixXd& values, int passes) {
  const Eigen::Index n = values.rows();
  if (passes <= 0 || n == 0) return values;
  // The rings as one flat list (offsets per vertex): the passes then stream through memory.
  std::vector<Eigen::Index> start(static_cast<std::size_t>(n) + 1, 0), next;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      if (F(f, j) >= 0 && F(f, j) < n) ++start[static_cast<std::size_t>(F(f, j)) + 1];
  for (std::size_t i = 0; i < static_cast<std::size_t>(n); ++i) start[i + 1] += start[i];
  next.resize(start.back());
  std::vector<Eigen::Index> fill(start.begin(), start.end() - 1);
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int j = 0; j < 3; ++j)
      if (F(f, j) >= 0 && F(f, j) < n) next[fill[F(f, j)]++] = F(f, (j + 1) % 3);
  Eigen::MatrixXd a = values, b(n, values.cols());
  for (int pass = 0; pass < passes; ++pass) {
    for (Eigen::Index c = 0; c < a.cols(); ++c)
      for (Eigen::Index i = 0; i < n; ++i) {
        double sum = a(i, c);
        for (Eigen::Index k = start[i]; k < start[i + 1]; ++k) sum += a(next[k], c);
        b(i, c) = sum / static_cast<double>(1 + start[i + 1] - start[i]);
      }
    a.swap(b);
  }
  return a;
}

}  // namespace colonmap::surface
