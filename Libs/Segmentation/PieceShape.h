#pragma once
// The two ends of one piece of colon lumen (a voxel mask), for ordering the pieces of a colon
// split by collapsed stretches (issue 21, PieceOrder.h). The mask is coarsened into blocks of
// about blockMm (each cell's 26-connected pieces of mask, so that no block straddles the thin
// wall between touching loops; a block's position is the mean of its voxels), geodesic
// distances run along the edges between touching blocks (Analysis/ShortestPaths.h),
// and the two ends are the geodesic extremities: the block farthest from any block, and the
// block farthest from that one.
#include "Core/Volume.h"

#include <Eigen/Core>

#include <array>

namespace colonmap::segmentation {

struct PieceEnd {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();    // LPS mm: centroid of the lumen 5-15 mm inside the end
  Eigen::Vector3d outward = Eigen::Vector3d::Zero();  // unit: the way the lumen runs out of the piece here
};

struct PieceShape {
  std::array<PieceEnd, 2> ends;
  double lengthMm = 0.0;  // geodesic length between the two extremities through the lumen (rim to rim:
                          // a little more than the centreline on a short wide piece)
};

// mask: non-zero inside the piece (one 26-connected component; any geometry). With L the
// length and d the geodesic distance from the other extremity, an end's point is the centroid
// of the lumen with d in [L - 15, L - 5] mm, its direction runs from the centroid of d in
// [L - 40, L - 25] mm to that point (the bands shrink to 10-30% and 45-60% of L on short
// pieces). Throws colonmap::Error for an empty mask.
PieceShape MeasurePieceShape(const Volume<unsigned char>& mask, double blockMm = 4.0);

}  // namespace colonmap::segmentation
