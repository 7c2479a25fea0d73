#pragma once
// Connected components of a binary grid, 26-connected (the foreground connectivity of the (26,6)
// pair), labelled like itk::ConnectedComponentImageFilter (FullyConnected) labels them, which
// stays behind as the reference of the tests (ItkSegmentationFilters.h). Our own because the
// host's Cancel must stop it: ITK's filter ran on 0.4 s after an Abort on a 1.2 mm CT (its
// phases check the abort flag rarely), this one polls `progress` every few slices.
//
// Runs of set voxels along i are linked across the four earlier rows that touch them in 26-
// connectivity (union-find on the runs, each set rooted at its first run). The labelling can stay
// as runs (ComponentRuns): a CT's air is a few runs per row, where a label grid is 4 bytes a voxel
// (472 MB for a clinical CT, most of the segmentation's memory and page faults).
#include "Segmentation/ItkSegmentationFilters.h"

#include <cstdint>
#include <vector>

namespace colonmap::segmentation::detail {

// The components as runs. Row r = j + n1 k holds runs [rowStart[r], rowStart[r + 1]), in order
// of i; labels 1..count are numbered in raster order of each component's first voxel (ITK's).
struct ComponentRuns {
  struct Run {
    std::uint32_t first, last;  // i of its first and last voxel
    std::uint32_t label;
  };
  std::vector<Run> runs;
  std::vector<std::size_t> rowStart;  // rows + 1 entries
  std::uint32_t count = 0;
};

// The components of the voxels with mask != 0.
ComponentRuns LabelComponentRuns26(const Grid& grid, const unsigned char* mask, ProgressSink& progress);
// The components of the voxels with value < threshold (a CT's air), without a mask in between.
ComponentRuns LabelComponentRunsBelow26(const Grid& grid, const short* values, short threshold, ProgressSink& progress);

// As a grid: labels[v] = 0 for background (mask 0), else the voxel's component 1..n. Returns n.
// With `labelsOfOne` false, `labels` is left empty when n is 1 (it would only repeat the mask).
std::uint32_t LabelComponents26(const Grid& grid, const unsigned char* mask, std::vector<std::uint32_t>& labels,
                                ProgressSink& progress, bool labelsOfOne = true);

// Cavities filled, in place: background voxels (0) that are not 6-connected to the grid border
// become foreground (1). With the (26,6) pair these are exactly the cavities of the 26-connected
// foreground. What itk::BinaryFillholeImageFilter with face connectivity does (the tests' reference,
// ItkFillCavities6), without its shape label map of the background (perimeters included) and with
// polls of `progress`.
void FillCavities6(const Grid& grid, std::vector<unsigned char>& mask, ProgressSink& progress);

}  // namespace colonmap::segmentation::detail
