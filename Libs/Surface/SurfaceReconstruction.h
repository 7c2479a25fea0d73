#pragma once
// Label map (optionally with its CT) -> closed triangle surface of the colon lumen (issue 4,
// DESIGN §2.1 stage 3).
//
//  1. Lumen mask: voxels whose label equals options.labelValue, cropped to their bounding box
//     plus a margin (the crop may extend past the image: outside counts as not lumen, so the
//     surface is always closed).
//  2. Sub-voxel contour (vtkFlyingEdges3D):
//     - with a CT: the iso-surface at options.isoValueHU (-480, half-way between air -1000 and
//       wall 40, where the partial-volume model puts the true wall) of the CT restricted to a
//       band of about options.bandVoxels around the label boundary: deeper inside the label
//       the value is set to air, farther outside to wall, so other air (small bowel, outside
//       air, lungs) cannot add surface and the surface cannot leave the band;
//     - without: the 0.5 iso-surface of the mask smoothed by a Gaussian of
//       options.labelSigmaVoxels.
//  3. Largest connected component kept (the others are reported).
//  4. Decimation to about options.targetFaces (vtkQuadricDecimation), removal of the rare
//     dangling "fin" triangles it leaves on a non-manifold edge, then windowed-sinc smoothing
//     (vtkWindowedSincPolyDataFilter: a low-pass filter that does not shrink folds).
//  5. To LPS (origin, spacing, direction of the label map), faces oriented so that normals
//     point INTO the lumen: each triangle's vertices run counter-clockwise seen from inside the
//     lumen (the closed surface has negative signed volume).
//  If the CT surface is not closed genus 0 (partial volume can bridge two lumen parts closer
//  than the band, where the label cut a handle), it is made again with the label deciding
//  inside and outside at the voxel centres (the CT placing the surface between them), then
//  from the label alone (notes). Pinch vertices left by the contour or the decimation are split.
//  6. Point data "MeanCurvature" (mm^-1, MeanCurvature.h: positive where the wall bulges into
//     the lumen, such as fold crests; about -1/(2r) on a plain tube of radius r).
// Progress is reported per stage step; VTK filters are aborted when the host cancels.
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"
#include "Core/Volume.h"
#include "Surface/MeshTopology.h"

#include <string>
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
  TopologyReport topology;             // of mesh
  long lumenVoxels = 0;                // voxels with the label value
  long contourFaces = 0;               // faces of the raw iso-surface (all components)
  std::vector<long> droppedComponents; // face counts of the components not kept, largest first
  bool usedCT = false;                 // the surface is the CT iso-surface (false: label only)
  // What was retried and why: with a CT, a surface with topology problems is made again with
  // the label deciding inside and outside at the voxel centres, and then from the label alone.
  std::vector<std::string> notes;
  // One line per problem found (non-manifold, handles, ...); empty when the surface is closed,
  // genus 0, manifold and consistently oriented.
  std::vector<std::string> problems;
};

// `ct` may be null (label-only path); when given it must be on the label map's grid.
// Throws colonmap::Error for an empty label (no voxel with the label value), a CT on another
// grid, or a contour that yields no surface; Cancelled when progress is cancelled.
SurfaceResult ReconstructSurface(const Volume<float>& label, const Volume<short>* ct,
                                 const SurfaceOptions& options, ProgressSink& progress);

}  // namespace colonmap::surface
