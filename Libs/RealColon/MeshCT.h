#pragma once
// Synthetic CT of a scan whose lumen is a closed triangle surface (the real-colon phantom,
// issue 17): the tube phantom's tissue model, partial-volume step, body, noise and tagged fluid
// (Phantom/SynthesizeCT.h), with the exact distance to the mesh in place of the tube's.
//
// Inside and outside: vtkPolyDataToImageStencil (ray parity, exact for a closed surface).
// Distance: exact point-triangle distance for the voxels within reach of the wall (the partial-
// volume half-width inside the lumen, the wall thickness plus it outside), each triangle
// rasterised over the voxels of its box, in parallel over slabs of slices. The outer wall is the
// lumen wall offset by the wall thickness (so loops that touch share one wall). Fluid: each pool
// is the lumen below a flat level connected to the pool's seed (flood fill), with the level's
// partial volume; the wall voxels next to it get the fluid of their lumen part. Collapsed
// stretches: the lumen holds wall (soft tissue) instead of air and fluid, with the
// partial-volume step along s at both ends.
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"
#include "Core/Volume.h"
#include "Phantom/PhantomOptions.h"

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

namespace colonmap::realcolon {

struct FluidPoolSpec {
  Eigen::Vector3d seed{0, 0, 0};  // a lumen point at the bottom of the pool (LPS mm)
  double level = 0.0;             // height of the air-fluid level: Height(p) = -down . p
};

struct MeshScan {
  const TriangleMesh* lumen = nullptr;  // closed surface of the lumen (LPS mm)
  Eigen::Vector3d down{0, 1, 0};        // gravity (supine +y, prone -y)
  std::vector<FluidPoolSpec> pools;
  double fluidHU = 750.0;
  std::uint64_t noiseKey = 0;           // seed of the noise (differs per scan)
  // Collapsed stretches (issue 21): material s ranges where the lumen is closed. A voxel takes
  // the material s of the point of this scan's axis (one point per material level, its s in
  // axisS) it is reached from first through the lumen.
  Eigen::MatrixXd axis;
  Eigen::VectorXd axisS;
  std::vector<std::pair<double, double>> collapsedS;
};

// CT on `grid` (origin, spacing, size set; identity direction): int16 HU. options.tissue and
// options.fluid are used. Progress over the whole call; Cancelled from progress.
void SynthesizeMeshCT(const MeshScan& scan, const phantom::PhantomOptions& options, Volume<short>& grid,
                      ProgressSink& progress);

// 1 inside the closed lumen surface, 0 elsewhere, on the geometry of `grid`.
Volume<unsigned char> MeshLumenMask(const TriangleMesh& lumen, const Volume<short>& grid);

// Voxels of each pool (pool index + 1; 0 elsewhere) on the mask's grid; exposed for tests.
Volume<unsigned char> FluidPools(const MeshScan& scan, const Volume<unsigned char>& mask, double halfWidth);

}  // namespace colonmap::realcolon
