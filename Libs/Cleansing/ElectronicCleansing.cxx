#include "Cleansing/ElectronicCleansing.h"

#include "Cleansing/TaggedMaterial.h"
#include "Core/Error.h"

#include <algorithm>
#include <cmath>

namespace colonmap::cleansing {
namespace {

// The index-space axis (0,1,2) and sign closest to a physical direction.
void DominantAxis(const Volume<short>& ct, const Eigen::Vector3d& down, int& axis, int& sign) {
  const Eigen::Vector3d inIndex = ct.direction.transpose() * down;
  inIndex.cwiseAbs().maxCoeff(&axis);
  sign = inIndex[axis] >= 0.0 ? 1 : -1;
}

}  // namespace

CleansingResult Cleanse(const Volume<short>& ct, const CleansingParameters& p, ProgressSink& progress) {
  CleansingResult r;
  r.cleansed = ct;
  r.tagged = ct.Like<unsigned char>(0);

  SubProgress find(progress, 0.0, 0.6);
  const TaggedMaterial tagged = FindTaggedMaterial(ct, p, find);
  r.regions = tagged.regions;
  r.regionsDropped = tagged.regionsDropped;
  r.fluidHU = tagged.fluidHU;
  r.down = tagged.down;
  r.gravityEstimated = tagged.gravityEstimated;
  r.gravityAgreement = tagged.levelAgreement;
  if (tagged.coreVoxels == 0) return r;  // untagged scan: unchanged
  if (r.fluidHU <= p.wallHU + 50.0) r.fluidHU = std::max(p.tagThresholdHU, p.wallHU + 50.0);

  int axis = 1, sign = 1;
  DominantAxis(ct, r.down, axis, sign);
  const long n[3] = {long(ct.size[0]), long(ct.size[1]), long(ct.size[2])};
  const int reach = std::max(1, p.partialVolumeVoxels);
  const double fluidMinusWall = r.fluidHU - p.wallHU;
  const double fluidMinusAir = r.fluidHU - p.airHU;

  // The partial-volume layer: every voxel within `reach` (box) of a core. Boxes are stamped
  // around core voxels that have a non-core face neighbour only: the interior adds nothing.
  Volume<unsigned char> layer = tagged.core;
  for (long k = 0; k < n[2]; ++k) {
    progress.Report(0.6 + 0.2 * double(k) / double(n[2]));
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        if (!tagged.core.At(i, j, k)) continue;
        const bool border = i == 0 || j == 0 || k == 0 || i + 1 == n[0] || j + 1 == n[1] || k + 1 == n[2] ||
                            !tagged.core.At(i - 1, j, k) || !tagged.core.At(i + 1, j, k) ||
                            !tagged.core.At(i, j - 1, k) || !tagged.core.At(i, j + 1, k) ||
                            !tagged.core.At(i, j, k - 1) || !tagged.core.At(i, j, k + 1);
        if (!border) continue;
        for (long c = std::max(0L, k - reach); c <= std::min(n[2] - 1, k + reach); ++c)
          for (long b = std::max(0L, j - reach); b <= std::min(n[1] - 1, j + reach); ++b)
            for (long a = std::max(0L, i - reach); a <= std::min(n[0] - 1, i + reach); ++a) layer.At(a, b, c) = 1;
      }
  }

  for (long k = 0; k < n[2]; ++k) {
    progress.Report(0.8 + 0.2 * double(k) / double(n[2]));
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        if (!layer.At(i, j, k)) continue;
        const double hu = ct.At(i, j, k);
        // Air above and fluid below along gravity: a voxel of the air-fluid level.
        bool airAbove = false, fluidBelow = tagged.core.At(i, j, k) != 0;
        for (int step = 1; step <= reach; ++step) {
          long up[3] = {i, j, k}, down[3] = {i, j, k};
          up[axis] -= sign * step;
          down[axis] += sign * step;
          if (up[axis] >= 0 && up[axis] < n[axis] && ct.At(up[0], up[1], up[2]) < p.airThresholdHU) airAbove = true;
          if (down[axis] >= 0 && down[axis] < n[axis] && tagged.core.At(down[0], down[1], down[2])) fluidBelow = true;
        }
        double phi = 0.0;  // fraction of tagged material in the voxel
        if (airAbove && fluidBelow) {
          phi = std::clamp((hu - p.airHU) / fluidMinusAir, 0.0, 1.0);
        } else {
          phi = std::clamp((hu - p.wallHU) / fluidMinusWall, 0.0, 1.0);
        }
        if (phi <= 0.0) continue;
        const double cleansed = hu - phi * fluidMinusAir;
        r.cleansed.At(i, j, k) = static_cast<short>(std::lround(std::clamp(cleansed, -1024.0, 3071.0)));
        ++r.taggedVoxels;
        if (phi >= 0.5) r.tagged.At(i, j, k) = 1;
      }
  }
  return r;
}

}  // namespace colonmap::cleansing
