#pragma once
// Connected components of a binary grid, 26-connected (the foreground connectivity of the (26,6)
// pair), labelled like itk::ConnectedComponentImageFilter (FullyConnected) labels them, which
// stays behind as the reference of the tests (ItkSegmentationFilters.h). Our own because the
// host's Cancel must stop it: ITK's filter ran on 0.4 s after an Abort on a 1.2 mm CT (its
// phases check the abort flag rarely), this one polls `progress` every slice.
#include "Segmentation/ItkSegmentationFilters.h"

#include <cstdint>
#include <vector>

namespace colonmap::segmentation::detail {

// labels[v] = 0 for background (mask 0), 1..n otherwise, numbered in raster order of each
// component's first voxel (deterministic, the same numbers as ITK's). Returns n. With
// `labelsOfOne` false, `labels` is left empty when n is 1 (it would only repeat the mask).
// Runs of set voxels along i are linked across the four earlier rows that touch them in 26-
// connectivity (union-find on the runs, each set rooted at its first run).
std::uint32_t LabelComponents26(const Grid& grid, const unsigned char* mask, std::vector<std::uint32_t>& labels,
                                ProgressSink& progress, bool labelsOfOne = true);

}  // namespace colonmap::segmentation::detail
