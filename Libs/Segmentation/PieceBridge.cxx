#include "Segmentation/PieceBridge.h"

#include <algorithm>
#include <cmath>

namespace colonmap::segmentation {

double Bridge::LengthMm() const {
  double length = 0.0;
  for (std::size_t i = 1; i < curve.size(); ++i) length += (curve[i] - curve[i - 1]).norm();
  return length;
}

Bridge MakeBridge(const PieceEnd& from, const PieceEnd& to, double radiusMm) {
  Bridge b;
  b.radiusMm = radiusMm;
  const double gap = (to.point - from.point).norm();
  const Eigen::Vector3d m0 = gap * from.outward, m1 = -gap * to.outward;
  // A Hermite curve is at most about 1.5 gaps long: this many samples keep them <= 0.5 mm apart.
  const int n = std::max(2, static_cast<int>(std::ceil(3.0 * gap / 0.5)) + 1);
  for (int i = 0; i < n; ++i) {
    const double t = double(i) / double(n - 1), t2 = t * t, t3 = t2 * t;
    b.curve.push_back((2 * t3 - 3 * t2 + 1) * from.point + (t3 - 2 * t2 + t) * m0 + (-2 * t3 + 3 * t2) * to.point +
                      (t3 - t2) * m1);
  }
  return b;
}

std::size_t DrawBridge(const Bridge& bridge, Volume<unsigned char>& mask, unsigned char value) {
  std::size_t added = 0;
  const double r = bridge.radiusMm;
  for (const Eigen::Vector3d& c : bridge.curve) {
    // The index box of the ball around this sample (any direction matrix: the box of the
    // ball's eight corners).
    Eigen::Vector3d lo = Eigen::Vector3d::Constant(1e300), hi = -lo;
    for (int corner = 0; corner < 8; ++corner) {
      const Eigen::Vector3d q(corner & 1 ? r : -r, corner & 2 ? r : -r, corner & 4 ? r : -r);
      const Eigen::Vector3d idx = mask.PhysicalToIndex(c + q);
      lo = lo.cwiseMin(idx);
      hi = hi.cwiseMax(idx);
    }
    long a[3], z[3];
    for (int d = 0; d < 3; ++d) {
      a[d] = std::max(0L, static_cast<long>(std::floor(lo[d])));
      z[d] = std::min(static_cast<long>(mask.size[d]) - 1, static_cast<long>(std::ceil(hi[d])));
    }
    for (long k = a[2]; k <= z[2]; ++k)
      for (long j = a[1]; j <= z[1]; ++j)
        for (long i = a[0]; i <= z[0]; ++i) {
          unsigned char& v = mask.At(std::size_t(i), std::size_t(j), std::size_t(k));
          if (v) continue;
          if ((mask.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k))) - c).squaredNorm() > r * r) continue;
          v = value;
          ++added;
        }
  }
  return added;
}

}  // namespace colonmap::segmentation
