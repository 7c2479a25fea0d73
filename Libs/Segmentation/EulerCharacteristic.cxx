#include "Segmentation/EulerCharacteristic.h"

#include <array>

namespace colonmap::segmentation {
namespace {

// For the 8 voxels around a lattice vertex (bit o: the voxel at offset -(o & 1), -(o >> 1 & 1),
// -(o >> 2 & 1)), 8 times the vertex's share of V - E + F - C: the vertex itself, minus half of
// each of its 6 edges, plus a quarter of each of its 12 faces, minus an eighth of each of its 8
// cubes, each cell present when one of the voxels around it is set. Summed over all lattice
// vertices, the shares count every cell once.
std::array<int, 256> ShareTable() {
  std::array<int, 256> t{};
  for (int c = 0; c < 256; ++c) {
    const auto set = [&](int o) { return (c >> o) & 1; };
    int v = c != 0 ? 8 : 0, e = 0, f = 0, cubes = 0;
    for (int axis = 0; axis < 3; ++axis) {
      // The two edges along `axis` at the vertex (one on each side) are touched by the 4
      // voxels on that side; the faces spanned by `axis` and another axis by the 2 voxels on
      // their side of the third axis.
      for (int side = 0; side < 2; ++side) {
        bool edge = false;
        for (int o = 0; o < 8; ++o)
          if (((o >> axis) & 1) == side && set(o)) edge = true;
        e += edge;
      }
    }
    for (int normal = 0; normal < 3; ++normal) {  // faces perpendicular to `normal`: 4 at the vertex
      const int a = (normal + 1) % 3, b = (normal + 2) % 3;
      for (int sa = 0; sa < 2; ++sa)
        for (int sb = 0; sb < 2; ++sb) {
          bool face = false;
          for (int o = 0; o < 8; ++o)
            if (((o >> a) & 1) == sa && ((o >> b) & 1) == sb && set(o)) face = true;
          f += face;
        }
    }
    for (int o = 0; o < 8; ++o) cubes += set(o);
    t[static_cast<std::size_t>(c)] = v - 4 * e + 2 * f - cubes;
  }
  return t;
}

}  // namespace

std::int64_t EulerCharacteristic(const Volume<unsigned char>& mask, ProgressSink* progress) {
  static const std::array<int, 256> share = ShareTable();
  const long n0 = static_cast<long>(mask.size[0]), n1 = static_cast<long>(mask.size[1]),
             n2 = static_cast<long>(mask.size[2]);
  const auto row = [&](long j, long k) -> const unsigned char* {
    return j >= 0 && k >= 0 && j < n1 && k < n2 ? &mask.voxels[static_cast<std::size_t>(n0 * (j + n1 * k))] : nullptr;
  };
  std::int64_t sum = 0;
  for (long k = 0; k <= n2; ++k) {
    if (progress && k % 8 == 0) progress->Report(double(k) / double(n2 + 1));
    for (long j = 0; j <= n1; ++j) {
      // The four voxel rows around this line of lattice vertices: bit 1 (j - 1), bit 2 (k - 1).
      const unsigned char* r[4] = {row(j, k), row(j - 1, k), row(j, k - 1), row(j - 1, k - 1)};
      if (!r[0] && !r[1] && !r[2] && !r[3]) continue;
      for (long i = 0; i <= n0; ++i) {
        int c = 0;
        for (int q = 0; q < 4; ++q) {
          if (!r[q]) continue;
          if (i < n0 && r[q][i]) c |= 1 << (2 * q);        // voxel at offset 0 along i
          if (i > 0 && r[q][i - 1]) c |= 1 << (2 * q + 1);  // at offset -1
        }
        // Reorder to the table's bit layout: o = (di) + 2 (dj) + 4 (dk), d = 1 for offset -1.
        int o = 0;
        for (int q = 0; q < 4; ++q)
          for (int di = 0; di < 2; ++di)
            if (c >> (2 * q + di) & 1) o |= 1 << (di + 2 * (q & 1) + 4 * (q >> 1));
        sum += share[static_cast<std::size_t>(o)];
      }
    }
  }
  if (progress) progress->Report(1.0);
  return sum / 8;
}

}  // namespace colonmap::segmentation
