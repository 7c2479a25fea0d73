#pragma once
// A lumen mask from any tool (another program's segmentation, a voxelised surface) made what
// the surface stage needs: one 26-connected component without cavities or handles (a
// topological ball, the topology our own segmentation gives, DESIGN 2.1), well-composed so
// that its contour is a closed manifold of the same topology (WellComposed.h).
//
// Steps: the largest 26-connected component is kept (the others are dropped and counted);
// its cavities are filled; its handles are counted from its Euler characteristic (for one
// component without cavities, handles = 1 - chi: EulerCharacteristic.h) and, when there are
// any, cut at their thinnest places by regrowing the lumen from its deepest voxel, deepest
// first, adding only simple points (TopologyPreservingGrowth.h, as the segmentation does); then
// the ball is made well-composed (WellComposed.h), and where that needs a voxel removed that is
// not a simple point, all steps run again. A mask that is already a ball skips the growth.
#include "Core/Cancel.h"
#include "Core/Volume.h"

#include <array>
#include <cstddef>
#include <vector>

namespace colonmap::segmentation {

struct LumenTopology {
  // The ball on a crop of the input's grid: the mask's box grown by `margin` voxels on every
  // side (it may reach past the image: those voxels are not lumen); origin, spacing and
  // direction set, so that IndexToPhysical gives LPS mm. first: the input index of crop voxel
  // (0, 0, 0).
  Volume<unsigned char> ball;
  std::array<long, 3> first{{0, 0, 0}};
  int components = 0;                   // 26-connected components of the input
  std::vector<std::size_t> dropped;     // voxel counts of the components left out, largest first
  std::size_t droppedVoxels = 0;        // their sum
  std::size_t cavityVoxelsFilled = 0;
  long handles = 0;                     // handles of the kept component
  std::size_t handleVoxelsRemoved = 0;  // voxels left out to cut them
  long wellComposedVoxels = 0;          // voxels changed to make it well-composed
  long forcedVoxels = 0;                // of those, removed although not simple points (the other
                                        // steps then ran again; 0 on all but voxel-rough masks)
  int rounds = 0;                       // passes of the steps (1 unless voxels were forced)
  std::size_t VoxelsChanged() const {
    return droppedVoxels + cavityVoxelsFilled + handleVoxelsRemoved + static_cast<std::size_t>(wellComposedVoxels);
  }
};

// The same in place on a mask (0/1) whose two outermost voxel layers are 0 (the caller's crop):
// the returned statistics leave `ball` empty and `first` zero. Throws colonmap::Error for an
// empty mask; Cancelled from progress.
LumenTopology MakeLumenBall(Volume<unsigned char>& mask, ProgressSink& progress);

// mask: non-zero voxels are lumen (any geometry). margin: at least 2. Throws colonmap::Error
// for an empty mask; Cancelled from progress.
LumenTopology SimplifyLumenTopology(const Volume<unsigned char>& mask, long margin, ProgressSink& progress);

}  // namespace colonmap::segmentation
