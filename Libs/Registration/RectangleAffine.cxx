#include "Registration/RectangleAffine.h"

#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace colonmap::registration {

Eigen::MatrixXd RectangleAffine::Apply(const Eigen::MatrixXd& uv) const {
  Eigen::MatrixXd out(uv.rows(), 2);
  for (Eigen::Index i = 0; i < uv.rows(); ++i) out.row(i) = Apply(Eigen::Vector2d(uv(i, 0), uv(i, 1))).transpose();
  return out;
}

RectangleAffine FitRectangleAffine(const Eigen::MatrixXd& supineUV, const Eigen::MatrixXd& proneUV, double shift) {
  const double s0 = supineUV.col(1).minCoeff(), s1 = supineUV.col(1).maxCoeff();
  const double p0 = proneUV.col(1).minCoeff(), p1 = proneUV.col(1).maxCoeff();
  if (!(s1 > s0) || !(p1 > p0)) throw Error("flat map has an empty length (v range)");
  RectangleAffine a;
  a.shift = shift;
  a.scale = (p1 - p0) / (s1 - s0);
  a.v0 = s0;
  a.v0Target = p0;
  return a;
}

namespace {

// Bilinear resampling onto around x along pixels, periodic in x, normalised.
std::vector<double> Resample(const Volume<float>& im, int around, int along) {
  const int nx = static_cast<int>(im.size[0]), ny = static_cast<int>(im.size[1]);
  if (nx < 1 || ny < 1 || im.voxels.size() < static_cast<std::size_t>(nx) * ny)
    throw Error("curvature image is empty");
  std::vector<double> out(static_cast<std::size_t>(around) * along);
  for (int j = 0; j < along; ++j) {
    const double y = std::clamp((j + 0.5) * ny / along - 0.5, 0.0, ny - 1.0);
    const int y0 = static_cast<int>(std::floor(y)), y1 = std::min(y0 + 1, ny - 1);
    const double fy = y - y0;
    for (int i = 0; i < around; ++i) {
      double x = (i + 0.5) * nx / around - 0.5;
      x -= nx * std::floor(x / nx);
      const int x0 = static_cast<int>(std::floor(x)) % nx, x1 = (x0 + 1) % nx;
      const double fx = x - std::floor(x);
      auto at = [&](int a, int b) { return static_cast<double>(im.At(a, b, 0)); };
      out[static_cast<std::size_t>(j) * around + i] = (1 - fy) * ((1 - fx) * at(x0, y0) + fx * at(x1, y0)) +
                                                      fy * ((1 - fx) * at(x0, y1) + fx * at(x1, y1));
    }
  }
  double mean = 0, var = 0;
  for (double v : out) mean += v;
  mean /= out.size();
  for (double& v : out) var += (v - mean) * (v - mean);
  const double sd = std::sqrt(var / out.size());
  for (double& v : out) v = sd > 0 ? (v - mean) / sd : 0.0;
  return out;
}

}  // namespace

CyclicShift CyclicShiftByCorrelation(const Volume<float>& supine, const Volume<float>& prone, int around, int along) {
  const std::vector<double> a = Resample(supine, around, along), b = Resample(prone, around, along);
  CyclicShift best;
  best.correlation = -2.0;
  for (int s = 0; s < around; ++s) {
    double c = 0;
    for (int j = 0; j < along; ++j)
      for (int i = 0; i < around; ++i)
        c += a[static_cast<std::size_t>(j) * around + i] * b[static_cast<std::size_t>(j) * around + (i + s) % around];
    c /= static_cast<double>(a.size());
    if (s == 0) best.correlationAtZero = c;
    if (c > best.correlation) {
      best.correlation = c;
      best.shift = s <= around / 2 ? static_cast<double>(s) / around : static_cast<double>(s - around) / around;
    }
  }
  return best;
}

}  // namespace colonmap::registration
