#pragma once
// The ITK filters the lumen segmentation uses, behind plain arrays. ITK 5.2 bundles its own
// Eigen 3.3, which must never share a translation unit with the system Eigen of Core/Volume.h:
// ItkSegmentationFilters.cxx includes ITK and nothing of Core but Error.h/Cancel.h, and the rest
// of Libs/Segmentation talks to it through this header (as Libs/IO/ItkImageBridge.h does).
//
// All images are i-fastest grids of `size` voxels with `spacing` mm (origin and direction do
// not matter to these filters). Each function reports progress through `progress` (a fraction
// of its own work, on the calling thread only) and stops with colonmap::Cancelled when the sink
// throws it; ITK failures become colonmap::Error.
#include "Core/Cancel.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace colonmap::segmentation::detail {

struct Grid {
  std::size_t size[3] = {0, 0, 0};
  double spacing[3] = {1, 1, 1};
  std::size_t Count() const { return size[0] * size[1] * size[2]; }
};

// itk::ConnectedComponentImageFilter, fully connected (26-neighbourhood): the reference the
// tests hold LabelComponents26 (LabelComponents.h) to. Same contract as that function, but the
// filter checks the host's Cancel rarely (0.4 s late on a 1.2 mm CT).
std::uint32_t ItkLabelComponents26(const Grid& grid, const unsigned char* mask, std::vector<std::uint32_t>& labels,
                                   ProgressSink& progress);

// itk::BinaryFillholeImageFilter with face connectivity: the reference the tests hold
// FillCavities6 (LabelComponents.h) to. Same contract.
void ItkFillCavities6(const Grid& grid, std::vector<unsigned char>& mask, ProgressSink& progress);

// itk::SignedMaurerDistanceMapImageFilter in mm (image spacing), exact Euclidean, inside
// positive: for a voxel with mask != 0, the distance from its centre to the nearest centre of a
// boundary voxel (a foreground voxel face-adjacent to background; boundary voxels get 0), so
// the radius of the largest inscribed ball is about this plus half a voxel. 0 for background.
void InsideDistance(const Grid& grid, const unsigned char* mask, std::vector<float>& distance,
                    ProgressSink& progress);

}  // namespace colonmap::segmentation::detail
