#pragma once
// A parallel loop over the voxels of a grid that reports progress and can be cancelled: the
// grid is walked in slabs of slices, voxels in parallel inside a slab (OpenMP), progress between
// slabs, so that a Cancelled exception never leaves an OpenMP region. Shared by the tube
// phantom's CT and the real-colon phantom's.
#include <Core/Cancel.h>
#include <Core/Volume.h>

#include <algorithm>

namespace colonmap {
namespace phantom {

// voxel(i, j, k) is called once per voxel, from several threads; it must only write its own voxel.
template <typename T, typename Voxel>
void ForEachVoxel(const Volume<T>& geometry, ProgressSink& progress, Voxel&& voxel) {
  const long nx = static_cast<long>(geometry.size[0]), ny = static_cast<long>(geometry.size[1]),
             nz = static_cast<long>(geometry.size[2]);
  const long slab = std::max(1L, 400000L / std::max(1L, nx * ny));
  progress.Report(0.0);
  for (long k0 = 0; k0 < nz; k0 += slab) {
    const long k1 = std::min(nz, k0 + slab);
    const long rows = (k1 - k0) * ny;
#pragma omp parallel for schedule(dynamic, 4)
    for (long r = 0; r < rows; ++r) {
      const long k = k0 + r / ny, j = r % ny;
      for (long i = 0; i < nx; ++i) voxel(i, j, k);
    }
    progress.Report(static_cast<double>(k1) / static_cast<double>(nz));
  }
}

}  // namespace phantom
}  // namespace colonmap
