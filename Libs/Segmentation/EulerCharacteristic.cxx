#include "Segmentation/EulerCharacteristic.h"

namespace colonmap::segmentation {

std::int64_t EulerCharacteristic(const Volume<unsigned char>& mask) {
  const long n0 = static_cast<long>(mask.size[0]), n1 = static_cast<long>(mask.size[1]),
             n2 = static_cast<long>(mask.size[2]);
  const auto in = [&](long i, long j, long k) {
    return i >= 0 && j >= 0 && k >= 0 && i < n0 && j < n1 && k < n2 && mask.At(i, j, k) != 0;
  };
  // A cell of the lattice belongs to the complex when one of the voxels (cubes) around it does.
  // A cell is named by its lowest lattice corner (i, j, k) and the axes it spans (bits of `axes`);
  // the cubes around it are those offset by 0 or -1 along each axis it does not span.
  std::int64_t chi = 0;
  for (int axes = 0; axes < 8; ++axes) {
    const int dimension = (axes & 1) + ((axes >> 1) & 1) + ((axes >> 2) & 1);
    const long extra[3] = {(axes & 1) ? 0 : 1, (axes & 2) ? 0 : 1, (axes & 4) ? 0 : 1};
    std::int64_t count = 0;
    for (long k = 0; k < n2 + extra[2]; ++k)
      for (long j = 0; j < n1 + extra[1]; ++j)
        for (long i = 0; i < n0 + extra[0]; ++i) {
          bool present = false;
          for (int o = 0; o < 8 && !present; ++o) {
            // Offsets only along the axes the cell does not span.
            if ((o & axes) != 0) continue;
            present = in(i - (o & 1), j - ((o >> 1) & 1), k - ((o >> 2) & 1));
          }
          count += present;
        }
    chi += (dimension % 2 == 0) ? count : -count;
  }
  return chi;
}

}  // namespace colonmap::segmentation
