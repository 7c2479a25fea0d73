#include "Views/FlatResampling.h"

#include "Core/Error.h"
#include "Registration/FlatLocator.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

namespace colonmap::views {

Eigen::MatrixXd FlatGrid::Centres() const {
  Eigen::MatrixXd c(static_cast<Eigen::Index>(nx) * ny, 2);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) c.row(static_cast<Eigen::Index>(j) * nx + i) = Centre(i, j).transpose();
  return c;
}

FlatGrid GridFor(double width, double height, double pixelsPerUnit) {
  if (!(width > 0) || !(height > 0) || !(pixelsPerUnit > 0)) throw Error("flat grid: width, height and pixels per unit must be positive");
  FlatGrid g;
  g.width = width;
  g.height = height;
  g.nx = std::max(1, static_cast<int>(std::lround(width * pixelsPerUnit)));
  g.ny = std::max(1, static_cast<int>(std::lround(height * pixelsPerUnit)));
  return g;
}

FlatPixelHits LocatePixels(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, double period, const FlatGrid& grid,
                           double tolerance, ProgressSink& progress) {
  if (F.rows() == 0 || uv.cols() != 2) throw Error("flat pixels: the flat mesh is empty or not 2D");
  const registration::FlatTriangleLocator locator(uv, F, period);
  const Eigen::Index n = static_cast<Eigen::Index>(grid.nx) * grid.ny;
  FlatPixelHits hits;
  hits.face = Eigen::VectorXi::Constant(n, -1);
  hits.bary = Eigen::MatrixXd::Zero(n, 3);
  auto last = std::chrono::steady_clock::now();
  for (int j = 0; j < grid.ny; ++j) {
    // Rows are cheap; report by time so that Cancel is seen within 0.2 s on any grid size.
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - last).count() > 0.1) {
      progress.Report(static_cast<double>(j) / grid.ny);
      last = now;
    }
    for (int i = 0; i < grid.nx; ++i) {
      const registration::FlatHit h = locator.Locate(grid.Centre(i, j));
      if (h.face < 0 || h.distance > tolerance) continue;
      const Eigen::Index p = static_cast<Eigen::Index>(j) * grid.nx + i;
      hits.face(p) = h.face;
      hits.bary.row(p) = h.bary.transpose();
    }
  }
  progress.Report(1.0);
  return hits;
}

Eigen::MatrixXd MapPixels(const FlatPixelHits& hits, const Eigen::MatrixXi& F, const Eigen::MatrixXd& targetUV,
                          double targetPeriod) {
  if (targetUV.cols() != 2) throw Error("flat pixels: target coordinates need 2 columns");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd out = Eigen::MatrixXd::Constant(hits.face.size(), 2, nan);
  for (Eigen::Index p = 0; p < hits.face.size(); ++p) {
    const int f = hits.face(p);
    if (f < 0) continue;
    Eigen::Vector2d c[3];
    for (int k = 0; k < 3; ++k) c[k] = targetUV.row(F(f, k)).transpose();
    if (targetPeriod > 0)
      for (int k = 1; k < 3; ++k) c[k].x() -= targetPeriod * std::round((c[k].x() - c[0].x()) / targetPeriod);
    out.row(p) = (hits.bary(p, 0) * c[0] + hits.bary(p, 1) * c[1] + hits.bary(p, 2) * c[2]).transpose();
  }
  return out;
}

Eigen::VectorXd FaceValuesAtPixels(const FlatPixelHits& hits, const Eigen::VectorXd& faceValues) {
  Eigen::VectorXd out = Eigen::VectorXd::Constant(hits.face.size(), std::numeric_limits<double>::quiet_NaN());
  for (Eigen::Index p = 0; p < hits.face.size(); ++p)
    if (hits.face(p) >= 0) {
      if (hits.face(p) >= faceValues.size()) throw Error("flat pixels: fewer face values than faces");
      out(p) = faceValues(hits.face(p));
    }
  return out;
}

Eigen::VectorXf SampleFlatImage(const Volume<float>& image, const Eigen::MatrixXd& uv, double unitsToMm, bool periodicU) {
  const int nx = static_cast<int>(image.size[0]), ny = static_cast<int>(image.size[1]);
  if (nx < 1 || ny < 1 || image.size[2] != 1 || image.voxels.size() != image.NumberOfVoxels())
    throw Error("flat image: not a 2D image");
  if (!(unitsToMm > 0)) throw Error("flat image: mm per flat unit must be positive");
  const double sx = image.spacing.x(), sy = image.spacing.y();
  const double ox = image.origin.x(), oy = image.origin.y();
  const float nan = std::numeric_limits<float>::quiet_NaN();
  Eigen::VectorXf out(uv.rows());
  auto at = [&](int i, int j) { return image.voxels[image.Offset(static_cast<std::size_t>(i), static_cast<std::size_t>(j), 0)]; };
  for (Eigen::Index p = 0; p < uv.rows(); ++p) {
    const double u = uv(p, 0) * unitsToMm, v = uv(p, 1) * unitsToMm;
    if (!std::isfinite(u) || !std::isfinite(v) || v < -0.5 * sy || v > (ny + 0.5) * sy) {
      out(p) = nan;
      continue;
    }
    // Continuous pixel index (pixel centres at integers).
    double x = (u - ox) / sx, y = std::clamp((v - oy) / sy, 0.0, ny - 1.0);
    int i0, i1;
    double fx;
    if (periodicU) {
      x = x - nx * std::floor(x / nx);  // [0, nx)
      i0 = static_cast<int>(std::floor(x));
      fx = x - i0;
      i0 %= nx;
      i1 = (i0 + 1) % nx;
    } else {
      x = std::clamp(x, 0.0, nx - 1.0);
      i0 = std::min(static_cast<int>(std::floor(x)), nx - 1);
      i1 = std::min(i0 + 1, nx - 1);
      fx = x - i0;
    }
    const int j0 = std::min(static_cast<int>(std::floor(y)), ny - 1), j1 = std::min(j0 + 1, ny - 1);
    const double fy = y - j0;
    const double a = at(i0, j0) * (1 - fx) + at(i1, j0) * fx, b = at(i0, j1) * (1 - fx) + at(i1, j1) * fx;
    out(p) = static_cast<float>(a * (1 - fy) + b * fy);
  }
  return out;
}

Eigen::MatrixXf PixelsToPicture(const Eigen::VectorXf& values, const FlatGrid& grid) {
  if (values.size() != static_cast<Eigen::Index>(grid.nx) * grid.ny) throw Error("flat picture: value count is not the grid size");
  Eigen::MatrixXf m(grid.ny, grid.nx);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) m(grid.ny - 1 - j, i) = values(static_cast<Eigen::Index>(j) * grid.nx + i);
  return m;
}

}  // namespace colonmap::views
