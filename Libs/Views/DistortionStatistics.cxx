#include "Views/DistortionStatistics.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace colonmap::views {

DilatationSummary SummarizeDilatation(const Eigen::VectorXd& K) {
  std::vector<double> v;
  DilatationSummary s;
  for (Eigen::Index k = 0; k < K.size(); ++k) {
    if (std::isfinite(K(k))) v.push_back(K(k));
    else ++s.infinite;
  }
  s.faces = static_cast<long>(v.size());
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (double x : v) sum += x;
  s.mean = sum / v.size();
  s.p99 = v[static_cast<std::size_t>(std::lround(0.99 * (v.size() - 1)))];
  s.max = v.back();
  return s;
}

Eigen::VectorXd DistortionAngle(const Eigen::VectorXd& beltramiArg) { return 0.5 * beltramiArg; }

}  // namespace colonmap::views
