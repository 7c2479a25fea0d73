#include "Cleansing/ElectronicCleansing.h"

#include "Cleansing/TaggedMaterial.h"
#include "Core/Error.h"

#include <boost/math/special_functions/erf.hpp>

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

namespace colonmap::cleansing {
namespace {

constexpr int kCleanColumnSearch = 8;        // voxels around a level voxel searched for clean columns
constexpr int kFarColumnSearch = 24;         // ... and how far when none is that near (shallow pools)
constexpr double kNoiseHU = 60.0;            // tolerated dip in a clean column's air-to-fluid ramp
constexpr double kFilmFraction = 0.02;       // film voxels: level fluid fraction within (this, 1 - this)
constexpr double kSaturated = 0.01;          // lumen fractions this close to 0 or 1 carry no position
constexpr double kIllConditionedHU = 150.0;  // lumen - wall contrast at which a voxel's own estimate weighs half

// The standard normal quantile and distribution: a Gaussian point-spread function's profile
// across a plane wall, the model for interpolating a wall's lumen fraction (see below).
double Probit(double x) { return std::sqrt(2.0) * boost::math::erf_inv(2.0 * x - 1.0); }
double NormalCdf(double t) { return 0.5 * std::erfc(-t / std::sqrt(2.0)); }

// The index-space axis (0,1,2) and sign closest to a physical direction.
void DominantAxis(const Volume<short>& ct, const Eigen::Vector3d& down, int& axis, int& sign) {
  const Eigen::Vector3d inIndex = ct.direction.transpose() * down;
  inIndex.cwiseAbs().maxCoeff(&axis);
  sign = inIndex[axis] >= 0.0 ? 1 : -1;
}

// Everything but the cleansed CT itself, reading `ct` only: its new values go to `changes`
// (offset, HU), to be written once all reads are done (the CT may be cleansed in place).
CleansingResult Analyse(const Volume<short>& ct, const CleansingParameters& p, ProgressSink& progress,
                        std::vector<std::pair<std::size_t, short>>& changes) {
  CleansingResult r;
  SubProgress find(progress, 0.0, 0.57), taggedStep(progress, 0.57, 0.585), layerStep(progress, 0.585, 0.6);
  const TaggedMaterial tagged = FindTaggedMaterial(ct, p, find);
  // No tagged voxel yet, made piece by piece (CT-sized).
  r.tagged = ct.Like<unsigned char>(0, &taggedStep);
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
  // The values of `layer`: partial-volume layer around a core (kLayer), a voxel of it on the
  // air-fluid level (kLevel, found once by levelTest below), the film zone (kZone, see there).
  constexpr unsigned char kLayer = 1, kZone = 2, kLevel = 3;
  Volume<unsigned char> layer = tagged.core.Copy(&layerStep);
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
            for (long a = std::max(0L, i - reach); a <= std::min(n[0] - 1, i + reach); ++a) layer.At(a, b, c) = kLayer;
      }
  }

  // A voxel of the air-fluid level: air above and tagged core below along gravity, within reach.
  // Air within `reach` above the voxel along gravity.
  const auto airAbove = [&](long i, long j, long k) {
    for (int step = 1; step <= reach; ++step) {
      long up[3] = {i, j, k};
      up[axis] -= sign * step;
      if (up[axis] >= 0 && up[axis] < n[axis] && ct.At(up[0], up[1], up[2]) < p.airThresholdHU) return true;
    }
    return false;
  };
  // A layer voxel with air above and tagged core below along gravity, within reach.
  const auto levelTest = [&](long i, long j, long k) {
    if (layer.At(i, j, k) != kLayer) return false;
    bool fluidBelow = tagged.core.At(i, j, k) != 0;
    for (int step = 1; step <= reach && !fluidBelow; ++step) {
      long down[3] = {i, j, k};
      down[axis] += sign * step;
      if (down[axis] >= 0 && down[axis] < n[axis] && tagged.core.At(down[0], down[1], down[2])) fluidBelow = true;
    }
    return fluidBelow && airAbove(i, j, k);
  };
  const auto isLevel = [&](long i, long j, long k) { return layer.At(i, j, k) == kLevel; };
  // Lumen fraction of a voxel that mixes wall with air only (above the level) or with fluid only
  // (below it).
  const auto lumenAbove = [&](double hu) { return std::clamp((p.wallHU - hu) / (p.wallHU - p.airHU), 0.0, 1.0); };
  const auto lumenBelow = [&](double hu) { return std::clamp((hu - p.wallHU) / fluidMinusWall, 0.0, 1.0); };

  // Fluid fraction s of the lumen at the height of voxel (i, j, k), read from the nearest clean
  // columns of the same level: columns with air above and fluid below and nothing else between,
  // where a voxel is air + fluid only. The level is flat, so s depends on the height alone.
  // Returns -1 when no clean column is near.
  const int lateral[2] = {(axis + 1) % 3, (axis + 2) % 3};
  // Memoised: the band's voxels ask for it several times (their own estimate, their neighbours').
  std::unordered_map<std::size_t, float> fractionCache;
  const auto searchFluidFraction = [&](long i, long j, long k) {
    const long at[3] = {i, j, k};
    double sum = 0.0;
    int found = 0;
    for (int radius = 1; radius <= kFarColumnSearch && found < 4 && !(found > 0 && radius > kCleanColumnSearch); ++radius)
      for (int a = -radius; a <= radius; ++a)
        for (int b = -radius; b <= radius; ++b) {
          if (std::max(std::abs(a), std::abs(b)) != radius || found >= 4) continue;
          long q[3] = {at[0], at[1], at[2]};
          q[lateral[0]] += a;
          q[lateral[1]] += b;
          long top[3] = {q[0], q[1], q[2]}, bottom[3] = {q[0], q[1], q[2]};
          top[axis] -= sign * (reach + 1);
          bottom[axis] += sign * (reach + 1);
          bool inside = true;
          for (int d = 0; d < 3; ++d)
            inside = inside && std::min({q[d], top[d], bottom[d]}) >= 0 && std::max({q[d], top[d], bottom[d]}) < n[d];
          if (!inside || ct.At(top[0], top[1], top[2]) >= p.airThresholdHU ||
              !tagged.core.At(bottom[0], bottom[1], bottom[2]))
            continue;
          // Air to fluid without a dip: no wall in between.
          bool monotone = true;
          double previous = p.airHU - kNoiseHU;
          for (int step = -(reach + 1); step <= reach + 1 && monotone; ++step) {
            long c[3] = {q[0], q[1], q[2]};
            c[axis] += sign * step;
            const double v = ct.At(c[0], c[1], c[2]);
            monotone = v >= previous - kNoiseHU;
            previous = std::max(previous, v);
          }
          if (!monotone) continue;
          sum += std::clamp((ct.At(q[0], q[1], q[2]) - p.airHU) / fluidMinusAir, 0.0, 1.0);
          ++found;
        }
    return found ? sum / found : -1.0;
  };
  const auto levelFluidFraction = [&](long i, long j, long k) {
    const std::size_t o = ct.Offset(std::size_t(i), std::size_t(j), std::size_t(k));
    if (const auto it = fractionCache.find(o); it != fractionCache.end()) return double(it->second);
    const double s = searchFluidFraction(i, j, k);
    fractionCache.emplace(o, float(s));
    return s;
  };

  // A film voxel: not core, near air (box of `reach`), tissue or fluid right below it along
  // gravity (not the fat beside or under a thin wall: measured on the phantom, voxels the fluid
  // did not touch that cleansing moved by > 100 HU: 234 / 202 without this test, 86 / 61 with
  // it, same surface; air straight above instead of near air missed films at the prone rims,
  // curvature SD 0.096 instead of 0.082), and at a height where the level's fluid fraction is
  // neither ~0 nor ~1.
  const auto isFilm = [&](long i, long j, long k) {
    if (ct.At(i, j, k) <= p.airThresholdHU || tagged.core.At(i, j, k)) return false;
    long below[3] = {i, j, k};
    below[axis] += sign;
    if (below[axis] < 0 || below[axis] >= n[axis] || ct.At(below[0], below[1], below[2]) < p.wallHU - kNoiseHU)
      return false;
    bool air = false;
    for (long c = std::max(0L, k - reach); c <= std::min(n[2] - 1, k + reach) && !air; ++c)
      for (long b = std::max(0L, j - reach); b <= std::min(n[1] - 1, j + reach) && !air; ++b)
        for (long a = std::max(0L, i - reach); a <= std::min(n[0] - 1, i + reach) && !air; ++a)
          air = ct.At(a, b, c) < p.airThresholdHU;
    if (!air) return false;
    const double s = levelFluidFraction(i, j, k);
    return s > kFilmFraction && s < 1.0 - kFilmFraction;
  };

  // Lumen fraction L of a voxel of the level band, and how well its value determines it. Where
  // the level meets the wall a voxel mixes air, fluid and wall:
  //   HU = L (air + s (fluid - air)) + (1 - L) wall,
  // with s, the fluid fraction of the lumen at that height, from the clean columns. Where the
  // lumen's mixed value is close to the wall's (s near 0.6) the equation says little (low weight).
  struct Estimate {
    double lumen = 1.0, weight = 0.0;
  };
  const auto threeMaterial = [&](long i, long j, long k) {
    Estimate e;
    const double s = levelFluidFraction(i, j, k);
    if (s < 0.0) return e;
    const double contrast = p.airHU + s * fluidMinusAir - p.wallHU;
    if (std::abs(contrast) < 1.0) return e;
    e.lumen = std::clamp((ct.At(i, j, k) - p.wallHU) / contrast, 0.0, 1.0);
    // Inverse-variance weight against the estimate interpolated from the voxels above and below:
    // the voxel's own error is noise / contrast; equal weights at kIllConditionedHU (measured on
    // the phantom's former levels: curvature SD 0.109 / 0.087 with a hard cut-off that ignored
    // the own estimate below that contrast, 0.092 / 0.085 with this weight).
    e.weight = contrast * contrast / (contrast * contrast + kIllConditionedHU * kIllConditionedHU);
    return e;
  };
  // Where the voxel's own estimate is weak, the wall's lumen fraction is interpolated along
  // gravity from the nearest voxels above and below that are well determined: level voxels with
  // a firm three-material estimate, or the first voxels past the band (air + wall above,
  // fluid + wall below: unambiguous). The band of weak estimates is about one voxel thick.
  const auto levelLumenFraction = [&](long i, long j, long k) {
    const Estimate own = threeMaterial(i, j, k);
    if (own.weight >= 0.95) return own.lumen;  // contrast >= 650 HU: the value decides
    const long at[3] = {i, j, k};
    double fraction[2] = {1.0, 1.0};
    int distance[2] = {0, 0};
    for (int side = 0; side < 2; ++side) {
      const int dir = side == 0 ? -sign : sign;  // 0: up, 1: down
      for (int step = 1; step <= 2 * reach + 1; ++step) {
        long q[3] = {at[0], at[1], at[2]};
        q[axis] += dir * step;
        if (q[axis] < 0 || q[axis] >= n[axis]) break;
        distance[side] = step;
        if (isLevel(q[0], q[1], q[2]) || isFilm(q[0], q[1], q[2])) {
          const Estimate e = threeMaterial(q[0], q[1], q[2]);
          if (e.weight < 0.5) continue;
          fraction[side] = e.lumen;
          break;
        }
        const double v = ct.At(q[0], q[1], q[2]);
        fraction[side] = side == 0 ? lumenAbove(v) : lumenBelow(v);
        break;
      }
    }
    const double total = std::max(1, distance[0] + distance[1]);
    // In the quantile of the fraction, not the fraction itself: through a plane wall a voxel's
    // lumen fraction is the PSF's cumulative profile of its distance to the wall, and that
    // distance is linear along gravity, so the quantile interpolates exactly (the PSF's width
    // cancels); the fraction, a step, does not (measured on the phantom's former levels,
    // seed 2: curvature SD 0.092 / 0.085 interpolating the fraction, 0.082 / 0.081 its
    // quantile; fluid-free 0.083 / 0.071). Fractions are clamped to [kSaturated, 1 - kSaturated]
    // first: a saturated neighbour only says that the wall is at least that far.
    const double a = Probit(std::clamp(fraction[0], kSaturated, 1.0 - kSaturated));
    const double b = Probit(std::clamp(fraction[1], kSaturated, 1.0 - kSaturated));
    const double interpolated = NormalCdf(a + (b - a) * double(distance[0]) / total);
    return own.weight * own.lumen + (1.0 - own.weight) * interpolated;
  };

  // Voxels of the level's heights that the level test misses: where the level grazes the wall
  // (the rim of a shallow pool, a floor nearly parallel to it) the fluid is a film thinner than
  // a voxel, no voxel of it is bright enough to be core, and the film's voxels mix air, fluid and
  // wall although no core lies below them; left as they are, their fluid reads as wall and the
  // surface sits up to half a voxel inside the lumen there (measured on the phantom before: up
  // to +900 HU against the fluid-free scan, 0.46 mm mean displacement on floors). Such voxels
  // lie within the clean columns' search radius of a level voxel, at its height: that zone is
  // marked (kZone in `layer`), and its film voxels (isFilm) are cleansed with the three-material
  // model too.
  std::vector<std::size_t> levelVoxels;
  for (long k = 0; k < n[2]; ++k)
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i)
        if (levelTest(i, j, k)) levelVoxels.push_back(ct.Offset(i, j, k));
  for (std::size_t o : levelVoxels) layer.voxels[o] = kLevel;
  for (std::size_t o : levelVoxels) {
    const long at[3] = {long(o % ct.size[0]), long((o / ct.size[0]) % ct.size[1]), long(o / (ct.size[0] * ct.size[1]))};
    for (int h = -reach; h <= reach; ++h)
      for (int a = -kCleanColumnSearch; a <= kCleanColumnSearch; ++a)
        for (int b = -kCleanColumnSearch; b <= kCleanColumnSearch; ++b) {
          long q[3] = {at[0], at[1], at[2]};
          q[axis] += h;
          q[lateral[0]] += a;
          q[lateral[1]] += b;
          if (q[0] < 0 || q[1] < 0 || q[2] < 0 || q[0] >= n[0] || q[1] >= n[1] || q[2] >= n[2]) continue;
          unsigned char& z = layer.At(q[0], q[1], q[2]);
          if (!z) z = kZone;
        }
  }
  for (long k = 0; k < n[2]; ++k) {
    progress.Report(0.8 + 0.2 * double(k) / double(n[2]));
    for (long j = 0; j < n[1]; ++j)
      for (long i = 0; i < n[0]; ++i) {
        const unsigned char zone = layer.At(i, j, k);
        if (!zone) continue;
        const double hu = ct.At(i, j, k);
        double cleansed = hu, phi = 0.0;  // phi: fraction of tagged material in the voxel
        const bool level = zone == kLevel;
        const bool film = !level && isFilm(i, j, k);
        if (level || film) {
          const double lumen = levelLumenFraction(i, j, k);
          cleansed = lumen * p.airHU + (1.0 - lumen) * p.wallHU;
          phi = std::clamp((hu - cleansed) / fluidMinusAir, 0.0, 1.0);
          if (cleansed >= hu) continue;  // nothing tagged to remove
        } else {
          if (zone != kLayer) continue;
          phi = std::clamp((hu - p.wallHU) / fluidMinusWall, 0.0, 1.0);
          if (phi <= 0.0) continue;
          cleansed = hu - phi * fluidMinusAir;
        }
        changes.emplace_back(ct.Offset(std::size_t(i), std::size_t(j), std::size_t(k)),
                             static_cast<short>(std::lround(std::clamp(cleansed, -1024.0, 3071.0))));
        ++r.taggedVoxels;
        if (phi >= 0.5) r.tagged.At(i, j, k) = 1;
      }
  }
  return r;
}

}  // namespace

CleansingResult Cleanse(Volume<short>&& ct, const CleansingParameters& p, ProgressSink& progress) {
  std::vector<std::pair<std::size_t, short>> changes;
  CleansingResult r = Analyse(ct, p, progress, changes);
  for (const auto& [offset, hu] : changes) ct.voxels[offset] = hu;
  r.cleansed = std::move(ct);
  return r;
}

CleansingResult Cleanse(const Volume<short>& ct, const CleansingParameters& p, ProgressSink& progress) {
  SubProgress copyStep(progress, 0.0, 0.03), rest(progress, 0.03, 1.0);
  return Cleanse(ct.Copy(&copyStep), p, rest);
}

}  // namespace colonmap::cleansing
