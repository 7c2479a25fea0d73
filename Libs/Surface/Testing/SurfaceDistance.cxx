#include "SurfaceDistance.h"

#include <algorithm>

namespace colonmap::surface::testing {

double Percentile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const std::size_t k = std::min(values.size() - 1, static_cast<std::size_t>(q * (values.size() - 1) + 0.5));
  std::nth_element(values.begin(), values.begin() + static_cast<long>(k), values.end());
  return values[k];
}

}  // namespace colonmap::surface::testing
