#pragma once
// Conversions between our Eigen types and VTK data objects, for the VTK filters used by the
// surface reconstruction. VTK types are only forward-declared here: callers create the VTK
// objects (vtkNew) in their own .cxx and pass them in.
//
// Image frame: VTK image filters here work on a "grid frame", the voxel index scaled by the
// spacing (origin 0, identity direction), because not every VTK 9.1 filter honours an image
// direction matrix. GridToPhysical maps grid-frame points to LPS with the volume's origin and
// direction (a rigid motion, possibly a reflection: callers fix orientation afterwards).
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"
#include "Core/Volume.h"

class vtkImageData;
class vtkPolyData;

namespace colonmap::surface {

// `image` (float scalars, grid frame) made to refer to the voxels of `volume`, without a copy:
// keep `volume` alive, and its voxels unmoved, while VTK filters read `image`.
void ToImageData(const Volume<float>& volume, vtkImageData* image);
// Copies float scalars of `image` (same dimensions) back into volume.voxels, polling
// `progress` (when given) as it goes.
void FromImageData(vtkImageData* image, Volume<float>& volume, ProgressSink* progress = nullptr);

// p = origin + direction * q for each row q of V (grid frame -> LPS mm).
template <typename T>
void GridToPhysical(const Volume<T>& volume, Eigen::MatrixXd& V) {
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    V.row(i) = (volume.origin + volume.direction * V.row(i).transpose()).transpose();
}

// Triangles and points (no data arrays) into `polyData`.
void ToPolyData(const TriangleMesh& mesh, vtkPolyData* polyData);
// Triangles and points of `polyData` (polygons with more than three vertices are fanned,
// other cells ignored); no data arrays.
TriangleMesh FromPolyData(vtkPolyData* polyData);

}  // namespace colonmap::surface
