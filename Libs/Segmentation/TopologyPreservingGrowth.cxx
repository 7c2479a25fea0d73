#include "Segmentation/TopologyPreservingGrowth.h"

#include "Core/Error.h"
#include "Segmentation/SimplePoint.h"

#include <chrono>
#include <cstdint>
#include <queue>
#include <utility>
#include <vector>

namespace colonmap::segmentation {
namespace {

enum State : unsigned char { kOutside = 0, kWaiting = 1, kQueued = 2, kGrown = 3 };

struct Later {
  // std::priority_queue pops the largest: higher priority first, then the lower offset.
  bool operator()(const std::pair<float, std::uint32_t>& a, const std::pair<float, std::uint32_t>& b) const {
    return a.first < b.first || (a.first == b.first && a.second > b.second);
  }
};

}  // namespace

Volume<unsigned char> GrowTopologicalBall(const Volume<unsigned char>& domain, const Volume<float>& priority,
                                          std::size_t seed, ProgressSink& progress,
                                          GrowthStatistics* statistics) {
  const auto start = std::chrono::steady_clock::now();
  const std::size_t n0 = domain.size[0], n1 = domain.size[1], n2 = domain.size[2];
  const std::size_t count = domain.NumberOfVoxels();
  if (priority.size != domain.size || priority.voxels.size() != count || domain.voxels.size() != count)
    throw Error("topology-preserving growth: domain and priority differ in size");
  if (count >= (std::size_t(1) << 32)) throw Error("topology-preserving growth: grid too large");
  if (seed >= count || !domain.voxels[seed]) throw Error("topology-preserving growth: the seed is not in the domain");

  std::vector<unsigned char> state(count, kOutside);
  std::size_t domainVoxels = 0;
  for (std::size_t k = 0; k < n2; ++k) {
    for (std::size_t j = 0; j < n1; ++j)
      for (std::size_t i = 0; i < n0; ++i) {
        const std::size_t v = domain.Offset(i, j, k);
        if (!domain.voxels[v]) continue;
        if (i == 0 || j == 0 || k == 0 || i + 1 == n0 || j + 1 == n1 || k + 1 == n2)
          throw Error("topology-preserving growth: the domain touches the grid border (pad it)");
        state[v] = kWaiting;
        ++domainVoxels;
      }
  }

  // Offsets of the 26 neighbours, indexed by their neighbourhood bit.
  std::int64_t offset[27];
  for (int dk = -1; dk <= 1; ++dk)
    for (int dj = -1; dj <= 1; ++dj)
      for (int di = -1; di <= 1; ++di)
        offset[NeighbourBit(di, dj, dk)] = di + static_cast<std::int64_t>(n0) * (dj + static_cast<std::int64_t>(n1) * dk);

  std::priority_queue<std::pair<float, std::uint32_t>, std::vector<std::pair<float, std::uint32_t>>, Later> queue;
  queue.emplace(priority.voxels[seed], static_cast<std::uint32_t>(seed));
  state[seed] = kQueued;
  std::size_t grown = 0, tests = 0, sinceReport = 0;
  while (!queue.empty()) {
    const std::uint32_t v = queue.top().second;
    queue.pop();
    if (++sinceReport == 8192) {
      sinceReport = 0;
      progress.Report(static_cast<double>(grown) / static_cast<double>(domainVoxels));
    }
    std::uint32_t neighbourhood = 0;
    for (int b = 0; b < 27; ++b)
      if (state[v + offset[b]] == kGrown) neighbourhood |= 1u << b;
    // The seed starts the ball; every later voxel must be simple (its neighbourhood is never
    // empty here, since it was queued by a grown neighbour).
    ++tests;
    if (grown > 0 && !IsSimple26(neighbourhood)) {
      state[v] = kWaiting;  // tried again if a neighbour is added later
      continue;
    }
    state[v] = kGrown;
    ++grown;
    for (int b = 0; b < 27; ++b) {
      const std::uint32_t w = static_cast<std::uint32_t>(v + offset[b]);
      if (state[w] == kWaiting) {
        state[w] = kQueued;
        queue.emplace(priority.voxels[w], w);
      }
    }
  }

  Volume<unsigned char> result = domain.Like<unsigned char>(0);
  for (std::size_t v = 0; v < count; ++v) result.voxels[v] = state[v] == kGrown;
  if (statistics) {
    statistics->domainVoxels = domainVoxels;
    statistics->grownVoxels = grown;
    statistics->refusedVoxels = domainVoxels - grown;
    statistics->simpleTests = tests;
    statistics->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  progress.Report(1.0);
  return result;
}

}  // namespace colonmap::segmentation
