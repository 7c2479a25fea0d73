#pragma once
// The true lumen surface of a scan as an open tube (topological cylinder): a grid over material
// s in [0, L] (step ~meshStepMm) and theta (meshPointsAround points, theta_j = 2 pi j / n).
// Vertex (i, j) has index i * n + j; faces are oriented so that their right-hand normals point
// into the lumen. Supine and prone walls share connectivity, so face k of one is the image of
// face k of the other under the true deformation.
// Point data: MaterialS (mm), MaterialTheta (rad, [0, 2 pi)), SegmentId (integer 0..4).
#include "PhantomOptions.h"
#include "ScanGeometry.h"

#include <Core/TriangleMesh.h>

namespace colonmap {
namespace phantom {

TriangleMesh TrueWall(const ScanGeometry& scan, const PhantomOptions& options);

}  // namespace phantom
}  // namespace colonmap
