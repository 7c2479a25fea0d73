#pragma once
// The true lumen wall of a real-colon phantom: any closed colon surface (an atlas weld with
// handles and touching loops, or a user's surface) made a closed, manifold, genus-0 triangle
// surface by construction, at a chosen grid, without decimation.
//
// Method: analysis::GenusZeroBall voxelises the surface, keeps the lumen one topological ball
// (cavities filled, each handle cut at its thinnest place by topology-preserving growth) and
// makes it well-composed. The ball smoothed by a Gaussian (sigma 0.7 voxel) and clamped so that
// its sign at every voxel centre is the ball's is contoured at 0.5 (vtkFlyingEdges3D): on a
// well-composed sign pattern that contour is a closed manifold with the ball's topology, so no
// repair or retry is needed. Windowed-sinc smoothing (vtkWindowedSincPolyDataFilter, which
// moves vertices only) then removes the voxel steps, except around the few faces it would push
// through others (their vertices keep the contour's positions). The result is checked (closed, one
// component, genus 0, manifold, consistently oriented; Error otherwise) and oriented with
// normals into the lumen (DESIGN 3.3).
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"

#include <cstddef>

namespace colonmap::realcolon {

struct TrueLumenOptions {
  double gridMm = 1.5;          // voxel size of the genus-0 step (finer keeps more haustral detail)
  int smoothingIterations = 20;  // windowed sinc
  double passBand = 0.05;
};

struct TrueLumen {
  TriangleMesh surface;               // closed genus 0, normals into the lumen, mm
  double lumenMl = 0.0;
  std::size_t handleVoxelsRemoved = 0;  // voxels the growth left out (where handles were cut)
  std::size_t cavityVoxelsFilled = 0;
  long wellComposedVoxels = 0;
  long restoredVertices = 0;  // vertices put back to the contour where smoothing made faces cross
};

// progress: fractions of this step; Cancelled from it.
TrueLumen MakeTrueLumen(const TriangleMesh& closedSurface, const TrueLumenOptions& options, ProgressSink& progress);

}  // namespace colonmap::realcolon
