#include "Views/DistortionTextures.h"

#include "Core/Error.h"

#include <cmath>
#include <limits>

namespace colonmap::views {
namespace {

double Cell(double width, const TextureOptions& o) {
  if (!(width > 0) || o.cellsAcross < 1) throw Error("texture: width and cells across must be positive");
  return width / o.cellsAcross;
}

}  // namespace

Eigen::VectorXd CheckerboardAt(const Eigen::MatrixXd& uv, double width, const TextureOptions& options) {
  const double c = Cell(width, options);
  Eigen::VectorXd out(uv.rows());
  for (Eigen::Index p = 0; p < uv.rows(); ++p) {
    if (!std::isfinite(uv(p, 0)) || !std::isfinite(uv(p, 1))) {
      out(p) = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    const double u = uv(p, 0) - width * std::floor(uv(p, 0) / width);
    const long k = static_cast<long>(std::floor(u / c)) + static_cast<long>(std::floor(uv(p, 1) / c));
    out(p) = (k % 2 + 2) % 2;
  }
  return out;
}

Eigen::VectorXd CirclesAt(const Eigen::MatrixXd& uv, double width, const TextureOptions& options) {
  const double c = Cell(width, options);
  Eigen::VectorXd out(uv.rows());
  for (Eigen::Index p = 0; p < uv.rows(); ++p) {
    if (!std::isfinite(uv(p, 0)) || !std::isfinite(uv(p, 1))) {
      out(p) = std::numeric_limits<double>::quiet_NaN();
      continue;
    }
    // Offset from the nearest cell centre, in cells.
    const double x = uv(p, 0) / c - std::floor(uv(p, 0) / c) - 0.5, y = uv(p, 1) / c - std::floor(uv(p, 1) / c) - 0.5;
    out(p) = std::hypot(x, y) <= options.circleRadius ? 1.0 : 0.0;
  }
  return out;
}

}  // namespace colonmap::views
