#pragma once
// Electronic cleansing (DESIGN §2.1): tagged fluid and stool become air, including their
// partial-volume layers, so that the wall under the fluid keeps its position and no ridge is
// left where the air-fluid level was.
//
// A voxel is a linear mixture of at most two materials at each interface. Near a tagged core:
//  - on the air-fluid level (air above it along gravity, fluid below), the voxel is air + fluid:
//    it becomes air;
//  - elsewhere (fluid against the wall), it is fluid + wall with fluid fraction
//    phi = (HU - wall) / (fluid - wall), and becomes HU - phi (fluid - air): the same mixture with
//    air in place of the fluid. The half-way value between air and wall then lies where the
//    half-way value between fluid and wall was, i.e. on the true wall;
//  - where the level meets the wall the voxel mixes air, fluid and wall: its lumen fraction
//    follows from its value and the fluid fraction of the lumen at that height (the level is
//    flat), read from clean air-over-fluid columns nearby; this includes the film of fluid a
//    shallow pool leaves where its level grazes a nearly horizontal wall, thinner than a voxel
//    and never bright enough to be found as fluid itself (see the .cxx).
// A scan without tagged material is returned unchanged.
#include "Cleansing/CleansingParameters.h"
#include "Core/Cancel.h"
#include "Core/Volume.h"

#include <Eigen/Core>
#include <cstddef>

namespace colonmap::cleansing {

struct CleansingResult {
  Volume<short> cleansed;
  Volume<unsigned char> tagged;  // 1 where the tagged fraction was at least one half
  std::size_t taggedVoxels = 0;  // voxels changed
  std::size_t regions = 0, regionsDropped = 0;
  double fluidHU = 0.0;
  Eigen::Vector3d down = Eigen::Vector3d::Zero();  // gravity used (LPS)
  bool gravityEstimated = false;
  double gravityAgreement = 0.0;
};

// The cleansed CT is a copy of `ct`; the overload on an rvalue cleanses it in place (no
// CT-sized copy: the module's own read of the file).
CleansingResult Cleanse(const Volume<short>& ct, const CleansingParameters& parameters, ProgressSink& progress);
CleansingResult Cleanse(Volume<short>&& ct, const CleansingParameters& parameters, ProgressSink& progress);

}  // namespace colonmap::cleansing
