#include "Views/FlatImageCorrelation.h"

#include "Core/Error.h"

#include <cmath>

namespace colonmap::views {

Correlation FlatImageCorrelation(const Eigen::VectorXf& a, const Eigen::VectorXf& b) {
  if (a.size() != b.size()) throw Error("flat correlation: the two pictures have different pixel counts");
  // Two passes (means, then centred sums) for accuracy.
  double sa = 0, sb = 0;
  long n = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (std::isfinite(a(k)) && std::isfinite(b(k))) {
      sa += a(k);
      sb += b(k);
      ++n;
    }
  Correlation c;
  c.pixels = n;
  if (n < 2) return c;
  const double ma = sa / n, mb = sb / n;
  double ab = 0, aa = 0, bb = 0;
  for (Eigen::Index k = 0; k < a.size(); ++k)
    if (std::isfinite(a(k)) && std::isfinite(b(k))) {
      const double x = a(k) - ma, y = b(k) - mb;
      ab += x * y;
      aa += x * x;
      bb += y * y;
    }
  if (aa > 0 && bb > 0) c.r = ab / std::sqrt(aa * bb);
  return c;
}

}  // namespace colonmap::views
