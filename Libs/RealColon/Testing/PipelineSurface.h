#pragma once
// A real-colon scan through our own CT -> surface stages, in-process as ColonSupineProne runs
// them: its CT, electronic cleansing, lumen segmentation, surface reconstruction.
#include "RealColon/RealColonPhantom.h"
#include "Surface/SurfaceReconstruction.h"

namespace colonmap::realcolon::testing {

struct PipelineSurface {
  surface::SurfaceResult surface;
  std::size_t taggedVoxels = 0;
  double lumenVolumeMl = 0.0;
};

PipelineSurface SurfaceFromCT(const RealColonPair& pair, phantom::Posture posture, const RealColonOptions& options);

}  // namespace colonmap::realcolon::testing
