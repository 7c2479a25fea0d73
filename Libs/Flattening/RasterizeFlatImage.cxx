#include "Flattening/RasterizeFlatImage.h"

#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace colonmap::flattening {

Volume<float> RasterizeFlatImage(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, const Eigen::VectorXd& values,
                                 double width, double height, int nx, int ny, RasterInfo* info, double period) {
  if (nx < 1 || ny < 1 || !(width > 0) || !(height > 0)) throw Error("flat image: empty size");
  const double sx = width / nx, sy = height / ny;
  Volume<float> image;
  image.size = {static_cast<std::size_t>(nx), static_cast<std::size_t>(ny), 1};
  image.spacing = Eigen::Vector3d(sx, sy, 1.0);
  image.origin = Eigen::Vector3d(0.5 * sx, 0.5 * sy, 0.0);
  image.Allocate(0.0f);
  std::vector<char> done(image.voxels.size(), 0);
  const int copies = period > 0.0 ? 3 : 1;
  for (int copy = 0; copy < copies; ++copy)
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    // Copy 0 unshifted first, so shifted copies only fill what the seam left open.
    const Eigen::Vector2d shift(copy == 0 ? 0.0 : copy == 1 ? -period : period, 0.0);
    const Eigen::Vector2d a = uv.row(F(f, 0)).transpose() + shift, b = uv.row(F(f, 1)).transpose() + shift,
                          c = uv.row(F(f, 2)).transpose() + shift;
    const double det = (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
    if (det == 0.0) continue;
    if (std::max({a.x(), b.x(), c.x()}) < 0.0 || std::min({a.x(), b.x(), c.x()}) > width) continue;
    const double eps = 1e-9;  // barycentric tolerance: pixel centres on shared edges are inside
    const int i0 = std::max(0, static_cast<int>(std::floor(std::min({a.x(), b.x(), c.x()}) / sx - 0.5)));
    const int i1 = std::min(nx - 1, static_cast<int>(std::ceil(std::max({a.x(), b.x(), c.x()}) / sx - 0.5)));
    const int j0 = std::max(0, static_cast<int>(std::floor(std::min({a.y(), b.y(), c.y()}) / sy - 0.5)));
    const int j1 = std::min(ny - 1, static_cast<int>(std::ceil(std::max({a.y(), b.y(), c.y()}) / sy - 0.5)));
    for (int j = j0; j <= j1; ++j)
      for (int i = i0; i <= i1; ++i) {
        const std::size_t o = image.Offset(static_cast<std::size_t>(i), static_cast<std::size_t>(j), 0);
        if (done[o]) continue;
        const double px = (i + 0.5) * sx, py = (j + 0.5) * sy;
        const double l1 = ((px - a.x()) * (c.y() - a.y()) - (py - a.y()) * (c.x() - a.x())) / det;
        const double l2 = ((b.x() - a.x()) * (py - a.y()) - (b.y() - a.y()) * (px - a.x())) / det;
        const double l0 = 1.0 - l1 - l2;
        if (l0 < -eps || l1 < -eps || l2 < -eps) continue;
        image.voxels[o] = static_cast<float>(l0 * values(F(f, 0)) + l1 * values(F(f, 1)) + l2 * values(F(f, 2)));
        done[o] = 1;
      }
  }
  RasterInfo r;
  r.covered = static_cast<long>(std::count(done.begin(), done.end(), 1));
  // Fill pixels no triangle covered from their filled 4-neighbours, ring by ring.
  for (bool changed = r.covered > 0; changed;) {
    changed = false;
    std::vector<char> next = done;
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) {
        const std::size_t o = image.Offset(static_cast<std::size_t>(i), static_cast<std::size_t>(j), 0);
        if (done[o]) continue;
        double sum = 0.0;
        int count = 0;
        const int di[4] = {-1, 1, 0, 0}, dj[4] = {0, 0, -1, 1};
        for (int k = 0; k < 4; ++k) {
          const int ii = i + di[k], jj = j + dj[k];
          if (ii < 0 || jj < 0 || ii >= nx || jj >= ny) continue;
          const std::size_t q = image.Offset(static_cast<std::size_t>(ii), static_cast<std::size_t>(jj), 0);
          if (done[q]) {
            sum += image.voxels[q];
            ++count;
          }
        }
        if (count > 0) {
          image.voxels[o] = static_cast<float>(sum / count);
          next[o] = 1;
          ++r.filled;
          changed = true;
        }
      }
    done.swap(next);
  }
  if (info) *info = r;
  return image;
}

}  // namespace colonmap::flattening
