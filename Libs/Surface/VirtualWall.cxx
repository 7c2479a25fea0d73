#include "Surface/VirtualWall.h"

#include <cmath>

namespace colonmap::surface {

Eigen::VectorXd VirtualVertices(const Eigen::MatrixXd& V, const Volume<unsigned char>& mask) {
  Eigen::VectorXd out = Eigen::VectorXd::Zero(V.rows());
  for (Eigen::Index v = 0; v < V.rows(); ++v) {
    const Eigen::Vector3d idx = mask.PhysicalToIndex(V.row(v).transpose());
    const long i0 = static_cast<long>(std::floor(idx.x())), j0 = static_cast<long>(std::floor(idx.y())),
               k0 = static_cast<long>(std::floor(idx.z()));
    for (int c = 0; c < 8 && out[v] == 0.0; ++c) {
      const long i = i0 + (c & 1), j = j0 + ((c >> 1) & 1), k = k0 + ((c >> 2) & 1);
      if (i < 0 || j < 0 || k < 0 || i >= long(mask.size[0]) || j >= long(mask.size[1]) || k >= long(mask.size[2])) continue;
      if (mask.At(std::size_t(i), std::size_t(j), std::size_t(k))) out[v] = 1.0;
    }
  }
  return out;
}

}  // namespace colonmap::surface
