#pragma once
// A virtual lumen through a collapsed stretch (issue 21): a tube along the smooth curve that
// leaves one piece's end the way its lumen runs out and enters the next piece's end the way
// that lumen runs in (a cubic Hermite curve, tangents the gap long), so that the pieces of a
// collapsed colon become one lumen again and every later stage sees one tube from caecum to
// rectum. The tube's wall is not real wall: the voxels it adds are kept apart, and everything
// that lands there is reported as not visible.
#include "Core/Volume.h"
#include "Segmentation/PieceShape.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::segmentation {

struct Bridge {
  std::vector<Eigen::Vector3d> curve;  // LPS mm, from `from` to `to`, every <= 0.5 mm
  double radiusMm = 0.0;
  double LengthMm() const;
};

// from: the end of the piece nearer the caecum, to: the end of the next piece.
Bridge MakeBridge(const PieceEnd& from, const PieceEnd& to, double radiusMm);

// Sets `value` in every zero voxel of `mask` whose centre lies within the bridge's radius of
// its curve; returns how many it set.
std::size_t DrawBridge(const Bridge& bridge, Volume<unsigned char>& mask, unsigned char value);

}  // namespace colonmap::segmentation
