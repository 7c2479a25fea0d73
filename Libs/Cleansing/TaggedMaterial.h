#pragma once
// Finds tagged fluid and stool: connected regions brighter than the tag threshold with an
// air-fluid level, i.e. a flat contact with lumen air. Bone is as bright, but where it comes
// near air (ribs by the lungs) the contact is not flat, and it is not horizontal; so a region is
// kept when the CT gradients at its air contact agree on one direction (a plane), and that
// direction is gravity (the gradient points from the air above to the fluid below). Regions
// whose median is barely above the threshold (partial volume of bone) are not fluid either.
#include "Cleansing/CleansingParameters.h"
#include "Core/Cancel.h"
#include "Core/Volume.h"

#include <Eigen/Core>
#include <cstddef>

namespace colonmap::cleansing {

struct TaggedMaterial {
  Volume<unsigned char> core;       // 1: confidently tagged voxel of a kept region
  std::size_t coreVoxels = 0;
  std::size_t regions = 0;          // bright regions kept
  std::size_t regionsDropped = 0;   // bright regions without a flat air contact (bone, vessels)
  double fluidHU = 0.0;             // median HU of the kept cores' interior voxels
  Eigen::Vector3d down = Eigen::Vector3d::Zero();  // gravity (given, or estimated from the levels)
  bool gravityEstimated = false;
  double levelAgreement = 0.0;      // mean flatness of the kept levels, in [0, 1]
};

// ct in HU. parameters.gravity (if non-zero) is trusted; otherwise gravity is the contact-weighted
// mean level direction of the flat regions, and regions whose level disagrees are dropped.
TaggedMaterial FindTaggedMaterial(const Volume<short>& ct, const CleansingParameters& parameters,
                                  ProgressSink& progress);

}  // namespace colonmap::cleansing
