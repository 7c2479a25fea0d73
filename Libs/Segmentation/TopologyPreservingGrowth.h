#pragma once
// Topology-preserving region growing (homotopic growth) for the (26,6) connectivity pair.
// Starting from one seed voxel, voxels of a domain are added in order of decreasing priority
// (for the lumen: depth, the distance to the air boundary), each only if it is a simple point
// of the grown set at that moment (SimplePoint.h). Adding simple points never changes
// topology, so the result is topologically a ball: one 26-connected component, no cavity, no
// handle (genus 0). Where the domain has a handle, the growth stops at the voxels that would
// close it, and since it runs deepest first those are the shallowest, thinnest places: the
// handle is cut where the cut is smallest. A voxel refused once is tried again whenever one of
// its neighbours is added (its neighbourhood changed), so the result does not depend on when a
// voxel first came up.
#include "Core/Cancel.h"
#include "Core/Volume.h"

#include <cstddef>

namespace colonmap::segmentation {

struct GrowthStatistics {
  std::size_t domainVoxels = 0;   // non-zero voxels of the domain
  std::size_t grownVoxels = 0;    // voxels of the result
  std::size_t refusedVoxels = 0;  // domain voxels left out because adding them changes topology
  std::size_t simpleTests = 0;    // simple-point tests made
  double seconds = 0.0;
};

// domain: non-zero voxels may be grown into; every voxel on the grid border must be zero (pad
// by one voxel), so that neighbourhoods never leave the grid. priority: same size, higher is
// grown first; ties are broken by the lower voxel offset (deterministic). seed: a voxel offset
// inside the domain. Returns a mask (1 grown, 0 not) with the domain's geometry. Calls
// progress.Report() every few tens of thousands of voxels; throws Cancelled from it.
Volume<unsigned char> GrowTopologicalBall(const Volume<unsigned char>& domain, const Volume<float>& priority,
                                          std::size_t seed, ProgressSink& progress,
                                          GrowthStatistics* statistics = nullptr);

}  // namespace colonmap::segmentation
