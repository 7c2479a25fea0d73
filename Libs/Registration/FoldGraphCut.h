#pragma once
// Fold regions of a flattened segment's curvature image by a graph cut (DESIGN §2.4, issue 7):
// a binary labelling fold / background of the pixel grid minimising
//   sum_p D_p(label_p) + smoothness * #{neighbouring pixel pairs with different labels},
//   D_p(fold) = min(clip, max(0, t - z_p)),  D_p(background) = min(clip, max(0, z_p - t)),
// z the robustly normalised mean curvature ((H - median) / (1.4826 MAD)), t its `quantile`;
// clipped so that one extreme pixel (a spike of the curvature, a polyp tip) cannot outweigh its
// neighbours.
// With smoothness 0 this is the plain threshold; the pairwise term removes isolated bright pixels
// (noise, a single ridge vertex) and bridges a fold interrupted by a pixel or two below the
// threshold, so the components follow whole folds. Solved exactly (a submodular binary energy)
// as the minimum s-t cut of the grid graph, 4-neighbourhood, periodic around the colon, by
// Boost.Graph's boykov_kolmogorov_max_flow on integer capacities (deterministic). Plain arrays
// in and out; Boost only in the .cxx.
#include <vector>

namespace colonmap::registration {

struct GraphCutOptions {
  double quantile = 0.88;    // t: the fold threshold as a quantile of z over the covered image
  double smoothness = 0.5;   // cost (in z units) of each pair of neighbours labelled differently
  double clip = 1.5;         // data costs capped at this (z units): an isolated pixel (4 edges,
                             // cost 2) is dropped, a 1-pixel-wide ridge (2 edges, cost 1) kept
};

struct FoldMask {
  std::vector<unsigned char> fold;  // rows x cols, row-major (1: fold)
  std::vector<float> z;             // the normalised curvature the data term used
  double threshold = 0.0;           // t, in z units
  long cutCost = 0;                 // the minimum energy (integer units: 1000 per z unit)
};

// image: rows x cols values, row-major (row = along the colon, column = around it), periodic in
// the columns when `periodic`. Throws colonmap::Error when the sizes do not match.
FoldMask SegmentFoldsByGraphCut(const std::vector<float>& image, int rows, int cols, bool periodic,
                                const GraphCutOptions& options = {});

}  // namespace colonmap::registration
