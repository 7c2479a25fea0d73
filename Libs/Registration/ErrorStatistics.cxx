#include "Registration/ErrorStatistics.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace colonmap::registration {

ErrorSummary SummarizeErrors(std::vector<double> e) {
  ErrorSummary s;
  s.count = static_cast<long>(e.size());
  if (e.empty()) return s;
  std::sort(e.begin(), e.end());
  auto q = [&](double f) {
    const double x = f * (e.size() - 1);
    const std::size_t i = static_cast<std::size_t>(std::floor(x));
    const std::size_t j = std::min(i + 1, e.size() - 1);
    return e[i] + (x - i) * (e[j] - e[i]);
  };
  s.mean = std::accumulate(e.begin(), e.end(), 0.0) / e.size();
  s.median = q(0.5);
  s.p90 = q(0.9);
  s.max = e.back();
  return s;
}

}  // namespace colonmap::registration
