#pragma once
// The voxels inside a closed triangle surface, libigl style: ray parity by
// vtkPolyDataToImageStencil (exact for a closed surface, whatever its topology).
#include "Core/TriangleMesh.h"
#include "Core/Volume.h"

namespace colonmap::surface {

// closed: a closed surface (LPS mm). mask: its origin, spacing and size give the grid (the
// direction must be the identity); every voxel is set to 1 inside the surface, 0 outside.
// Throws colonmap::Error for a grid with another direction.
void FillInsideMask(const TriangleMesh& closed, Volume<unsigned char>& mask);

}  // namespace colonmap::surface
