#pragma once
// Which wall of a registration mesh was seen in its CT (issue 21). Where a stretch was
// collapsed, ColonSegmentation bridged it with virtual lumen, and the surface marks that wall
// Virtual = 1 (ColonSurface; the array rides along to registration.vtp and its prone mesh). A
// point that lands there has no true position in that scan: it is reported as not visible,
// with the nearest open wall along the colon instead.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>
#include <vector>

namespace colonmap::registration {

struct OpenPlace {
  int vertex = -1;            // nearest open vertex (-1: the mesh has no open vertex)
  double alongColonMm = 0.0;  // |CenterlineArcLength difference| (3D distance without that array)
};

class WallVisibility {
 public:
  // mesh: kept by reference. Without a Virtual point array every place is visible.
  explicit WallVisibility(const TriangleMesh& mesh);

  bool HasVirtualWall() const { return hasVirtual_; }
  // Virtual interpolated at a point of a face (0 open .. 1 virtual); 0 without the array.
  double VirtualAt(int face, const Eigen::Vector3d& bary) const;
  // The open vertex nearest along the colon (by CenterlineArcLength; among the vertices within
  // 2 mm of the least arc-length difference, the nearest in 3D) to a point of a face.
  OpenPlace NearestOpen(int face, const Eigen::Vector3d& bary) const;
  // Distance (mm) from a point to the nearest vertex on virtual wall; infinite without any.
  double DistanceToVirtual(const Eigen::Vector3d& point) const;
  // Whether a point `wallDistanceMm` from the nearest open wall lies off the seen wall, inside a
  // collapsed stretch: more than offWallMm from it and virtual wall within that distance plus
  // nearVirtualMm (issue 21: an evaluation point 0-14 mm into a collapse; a finding marked on
  // seen wall, even a polyp's tip, is within about 2 mm of the surface).
  bool OffSeenWall(const Eigen::Vector3d& point, double wallDistanceMm) const;
  static constexpr double offWallMm = 3.0, nearVirtualMm = 15.0;

 private:
  const TriangleMesh& mesh_;
  bool hasVirtual_ = false;
  Eigen::VectorXd virtual_, arc_;  // arc_ empty without CenterlineArcLength
  std::vector<Eigen::Index> virtualVertices_;
};

}  // namespace colonmap::registration
