#pragma once
// Euler characteristic of a voxel set seen as the union of its closed unit cubes (which is the
// topology of the (26,6) connectivity pair): chi = V - E + F - C, counting the distinct
// vertices, edges, faces and cubes of that cubical complex. chi = (components) - (handles) +
// (cavities): 1 for a solid ball, 0 for a solid torus, 2 for a ball with one cavity. An
// independent check of the simple-point growth (which uses no such counting).
#include "Core/Cancel.h"
#include "Core/Volume.h"

#include <cstdint>

namespace colonmap::segmentation {

// Voxels with a non-zero value form the set. `progress`, when given, is polled every few slices.
std::int64_t EulerCharacteristic(const Volume<unsigned char>& mask, ProgressSink* progress = nullptr);

}  // namespace colonmap::segmentation
