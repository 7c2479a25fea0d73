#include "Cleansing/TaggedMaterial.h"

#include <algorithm>
#include <array>
#include <vector>

namespace colonmap::cleansing {
namespace {

constexpr std::array<std::array<int, 3>, 6> kFaceNeighbours = {
    {{{1, 0, 0}}, {{-1, 0, 0}}, {{0, 1, 0}}, {{0, -1, 0}}, {{0, 0, 1}}, {{0, 0, -1}}}};

// A level must be a plane: unit gradients at the contact agree at least this much, over at least
// this many voxels.
constexpr double kMinimumFlatness = 0.6;
constexpr std::size_t kMinimumContacts = 8;
// A region's median must exceed the tag threshold by this much.
constexpr double kMedianMarginHU = 100.0;
// A kept level's direction must agree this well with gravity.
constexpr double kMinimumAlignment = 0.8;

bool Inside(const Volume<short>& v, long i, long j, long k) {
  return i >= 0 && j >= 0 && k >= 0 && i < long(v.size[0]) && j < long(v.size[1]) && k < long(v.size[2]);
}

// True when a voxel within `reach` voxels (box) is confidently air: the air-fluid level's
// partial-volume ramp separates the two by up to about two voxels.
bool NearAir(const Volume<short>& ct, long i, long j, long k, double airThreshold, long reach) {
  for (long c = k - reach; c <= k + reach; ++c)
    for (long b = j - reach; b <= j + reach; ++b)
      for (long a = i - reach; a <= i + reach; ++a)
        if (Inside(ct, a, b, c) && ct.At(a, b, c) < airThreshold) return true;
  return false;
}

// CT gradient in LPS (central differences, spacing and direction honoured).
Eigen::Vector3d Gradient(const Volume<short>& ct, long i, long j, long k) {
  const auto at = [&](long a, long b, long c) {
    a = std::clamp(a, 0L, long(ct.size[0]) - 1);
    b = std::clamp(b, 0L, long(ct.size[1]) - 1);
    c = std::clamp(c, 0L, long(ct.size[2]) - 1);
    return double(ct.At(a, b, c));
  };
  const Eigen::Vector3d g((at(i + 1, j, k) - at(i - 1, j, k)) / (2.0 * ct.spacing[0]),
                          (at(i, j + 1, k) - at(i, j - 1, k)) / (2.0 * ct.spacing[1]),
                          (at(i, j, k + 1) - at(i, j, k - 1)) / (2.0 * ct.spacing[2]));
  return ct.direction * g;
}

struct Region {
  std::vector<std::size_t> voxels;
  Eigen::Vector3d gradientSum = Eigen::Vector3d::Zero();  // of unit gradients at the air contact
  std::size_t contacts = 0;
  double Flatness() const { return contacts ? gradientSum.norm() / double(contacts) : 0.0; }
  Eigen::Vector3d Direction() const { return gradientSum.normalized(); }
};

}  // namespace

TaggedMaterial FindTaggedMaterial(const Volume<short>& ct, const CleansingParameters& p, ProgressSink& progress) {
  TaggedMaterial result;
  SubProgress coreStep(progress, 0.0, 0.06);
  result.core = ct.Like<unsigned char>(0, &coreStep);
  const long reach = std::max(1, p.partialVolumeVoxels);
  // The flood marks the voxels it has seen in `core` itself (kSeen); the kept regions' voxels
  // become 1 at the end and the marks go (no second CT-sized buffer).
  constexpr unsigned char kSeen = 2;
  std::vector<unsigned char>& visited = result.core.voxels;
  std::vector<Region> flat;
  std::vector<std::size_t> queue;
  const std::size_t nx = ct.size[0], ny = ct.size[1], nz = ct.size[2];
  for (std::size_t k = 0; k < nz; ++k) {
    progress.Report(0.06 + 0.84 * double(k) / double(nz));
    for (std::size_t j = 0; j < ny; ++j) {
      for (std::size_t i = 0; i < nx; ++i) {
        const std::size_t start = ct.Offset(i, j, k);
        if (visited[start] || ct.voxels[start] <= p.tagThresholdHU) continue;
        // Flood one bright region (6-connected); its border voxels near air vote for the level.
        Region region;
        queue.assign(1, start);
        visited[start] = kSeen;
        while (!queue.empty()) {
          const std::size_t o = queue.back();
          queue.pop_back();
          region.voxels.push_back(o);
          const long x = long(o % nx), y = long((o / nx) % ny), z = long(o / (nx * ny));
          bool border = false;
          for (const auto& d : kFaceNeighbours) {
            const long a = x + d[0], b = y + d[1], c = z + d[2];
            if (!Inside(ct, a, b, c)) continue;
            const std::size_t n = ct.Offset(a, b, c);
            if (ct.voxels[n] <= p.tagThresholdHU) {
              border = true;
            } else if (!visited[n]) {
              visited[n] = kSeen;
              queue.push_back(n);
            }
          }
          if (border && NearAir(ct, x, y, z, p.airThresholdHU, reach)) {
            const Eigen::Vector3d g = Gradient(ct, x, y, z);
            if (g.norm() > 0.0) {
              region.gradientSum += g.normalized();
              ++region.contacts;
            }
          }
          if (region.voxels.size() % 65536 == 0) progress.Report(0.06 + 0.84 * double(k) / double(nz));
        }
        // Tagged fluid is several hundred HU through and through; a region barely above the
        // threshold is partial volume of bone or vessels.
        std::vector<short> values;
        values.reserve(region.voxels.size());
        for (std::size_t o : region.voxels) values.push_back(ct.voxels[o]);
        std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
        const bool bright = values[values.size() / 2] >= p.tagThresholdHU + kMedianMarginHU;
        if (bright && region.contacts >= kMinimumContacts && region.Flatness() >= kMinimumFlatness)
          flat.push_back(std::move(region));
        else
          ++result.regionsDropped;
      }
    }
  }

  // Gravity: given, or the contact-weighted mean of the flat levels.
  if (p.gravity.norm() > 0.0) {
    result.down = p.gravity.normalized();
  } else {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const Region& r : flat) sum += r.gradientSum;
    if (sum.norm() > 0.0) {
      result.down = sum.normalized();
      result.gravityEstimated = true;
    }
  }
  SubProgress clearStep(progress, 0.9, 0.95);
  ForPieces(visited.size(), kPollPiece, &clearStep, [&](std::size_t b, std::size_t e) {
    for (std::size_t v = b; v < e; ++v) visited[v] = 0;
  });
  double flatness = 0.0;
  for (const Region& r : flat) {
    if (result.down.norm() == 0.0 || r.Direction().dot(result.down) < kMinimumAlignment) {
      ++result.regionsDropped;
      continue;
    }
    ++result.regions;
    flatness += r.Flatness();
    for (std::size_t o : r.voxels) result.core.voxels[o] = 1;
    result.coreVoxels += r.voxels.size();
  }
  if (result.regions) result.levelAgreement = flatness / double(result.regions);
  progress.Report(0.95);

  // The fluid's own HU, from kept voxels away from every boundary (all 6 neighbours kept too).
  std::vector<short> interior;
  for (std::size_t o = 0; o < result.core.voxels.size(); ++o) {
    if (!result.core.voxels[o]) continue;
    const long x = long(o % nx), y = long((o / nx) % ny), z = long(o / (nx * ny));
    bool deep = true;
    for (const auto& d : kFaceNeighbours) {
      const long a = x + d[0], b = y + d[1], c = z + d[2];
      deep = deep && Inside(ct, a, b, c) && result.core.voxels[ct.Offset(a, b, c)];
    }
    if (deep) interior.push_back(ct.voxels[o]);
  }
  if (!interior.empty()) {
    std::nth_element(interior.begin(), interior.begin() + interior.size() / 2, interior.end());
    result.fluidHU = interior[interior.size() / 2];
  }
  return result;
}

}  // namespace colonmap::cleansing
