#pragma once
// Label map (optionally with its CT) -> closed genus-0 triangle surface of the colon lumen, in
// one pass, manifold by construction (DESIGN 2.1 stage 3).
//
//  1. Lumen mask: voxels whose label equals options.labelValue, on a crop of the label's grid
//     around them (the crop may extend past the image: outside counts as not lumen), made one
//     topological ball whatever tool made it (segmentation::MakeLumenBall: the largest
//     component, cavities filled, handles cut at their thinnest places, well-composed).
//  2. The field to contour:
//     - with a CT: the iso-surface at options.isoValueHU (-480, half-way between air -1000 and
//       wall 40, where the partial-volume model puts the true wall) of the CT restricted to a
//       band of about options.bandVoxels around the ball's boundary (deeper inside set to air,
//       farther outside to wall, so other air cannot add surface);
//     - without: the ball smoothed by a Gaussian of options.labelSigmaVoxels (iso-value 0.5).
//  3. Label only: its contour (vtkFlyingEdges3D; largest component) when that is one closed
//     genus-0 surface (the smoothing rounds the cuts).
//  4. Otherwise (always with a CT) the field's sign at every voxel centre made the ball's where
//     it differs (the voxel moved just past the iso-value: the field still places the surface
//     between voxel centres, the ball decides which side they are on), and its contour: on a
//     well-composed sign pattern a closed manifold with the ball's topology (one pass with a CT;
//     at most two without).
//  4. Decimation to about options.targetFaces that keeps it a closed manifold of the same
//     topology (ManifoldDecimation.h), then windowed-sinc smoothing (vertices only).
//  5. To LPS (origin, spacing, direction of the label map), faces oriented so that normals
//     point INTO the lumen: each triangle's vertices run counter-clockwise seen from inside the
//     lumen (the closed surface has negative signed volume).
//  6. Point data "MeanCurvature" (mm^-1, MeanCurvature.h: positive where the wall bulges into
//     the lumen, such as fold crests; about -1/(2r) on a plain tube of radius r).
// What the topology step changed is in `changes` and `notes`. A result that is not a closed
// genus-0 surface is an Error (never returned). Progress is reported per step; VTK filters are
// aborted when the host cancels.
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"
#include "Core/Volume.h"
#include "Segmentation/LumenTopology.h"
#include "Surface/MeshTopology.h"

#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::surface {

struct SurfaceOptions {
  double labelValue = 1.0;      // lumen voxels: label == labelValue (compared after rounding)
  long targetFaces = 200000;    // about this many faces after decimation (no decimation if fewer)
  double isoValueHU = -480.0;   // CT path: iso-value of the lumen wall
  double airHU = -1000.0;       // CT path: value set deep inside the label
  double wallHU = 40.0;         // CT path: value set far outside the label
  double bandVoxels = 2.5;      // CT path: half-width of the band around the label boundary
  double labelSigmaVoxels = 0.7;  // label path: Gaussian smoothing of the mask before contouring
  // Windowed sinc after decimation. Measured on the phantom (1.5 mm, 60K faces, CT path): 5
  // iterations at pass band 0.1 keep the distance to the true wall (mean 0.05 mm) and improve
  // the curvature; 10-20 iterations moved the wall by 0.1-0.2 mm on average.
  int smoothingIterations = 5;
  double smoothingPassBand = 0.1;
};

struct SurfaceResult {
  TriangleMesh mesh;                   // faces oriented into the lumen, point data MeanCurvature
  TopologyReport topology;             // of mesh: always closed genus 0
  long lumenVoxels = 0;                // voxels with the label value
  long contourFaces = 0;               // faces of the raw iso-surface
  std::vector<long> droppedComponents; // voxel counts of the lumen components not kept, largest first
  bool usedCT = false;                 // the surface is the CT iso-surface (false: label only)
  segmentation::LumenTopology changes; // what the topology step changed (its `ball` empty)
  std::size_t voxelsChanged = 0;       // voxels the topology step changed (dropped, filled, cut, well-composed)
  int contourPasses = 0;               // 1; 2 when a label-only lumen's smoothed surface had to be remade
  std::vector<std::string> notes;      // the same in words, one line each
  std::vector<std::pair<std::string, double>> stepSeconds;  // topology, field, contour, decimation, smoothing, ...
};

// Whether a label map's voxel holds the label value (integer labels read as any type).
template <typename T>
bool IsLabel(T voxel, double value) {
  return std::fabs(static_cast<float>(voxel) - static_cast<float>(value)) < 0.5f;
}

// `ct` may be null (label-only path); when given it must be on the label map's grid.
// Throws colonmap::Error for an empty label (no voxel with the label value), a CT on another
// grid, or a contour that yields no surface; Cancelled when progress is cancelled.
SurfaceResult ReconstructSurface(const Volume<float>& label, const Volume<short>* ct,
                                 const SurfaceOptions& options, ProgressSink& progress);

// The same from the lumen's mask on the label map's grid (every non-zero voxel is lumen: not a
// label map of several labels, see LumenMask). ColonSurface makes the mask as it takes the label
// map, without a float copy of a CT-sized volume (options.labelValue then only names the label
// in messages).
SurfaceResult ReconstructSurfaceFromMask(const Volume<unsigned char>& lumen, const Volume<short>* ct,
                                         const SurfaceOptions& options, ProgressSink& progress);

// 1 where |label - value| < 0.5, else 0; `progress`, when given, polled between pieces.
template <typename T>
Volume<unsigned char> LumenMask(const Volume<T>& label, double value, ProgressSink* progress = nullptr) {
  return MapVoxels<unsigned char>(label, [value](T v) { return IsLabel(v, value); }, progress);
}

}  // namespace colonmap::surface
