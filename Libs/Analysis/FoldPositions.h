#pragma once
// Haustral folds from a radius profile, libigl style. A fold is a crescent ridge that narrows
// the lumen over part of the circumference for ~1 cm of length, so it shows as a local minimum
// of the radius profile of the angular sectors it covers. Method, per sector profile of a
// TubeProfile (or of the all-angle profile with perSector = false):
//   1. Gaussian smoothing along the arc (sigma smoothingMm), NaN-aware: bins without a value
//      do not count; where no valid bin lies within maxGapMm the smoothed profile is NaN and
//      the profile splits into runs there.
//   2. Local minima inside a run (not at its ends).
//   3. Prominence of a minimum: walk left, within windowMm and the run, until a lower value;
//      the highest value passed is the left barrier; the same to the right; prominence =
//      min(left barrier, right barrier) - value. Keep minima with prominence >=
//      minProminenceMm and >= minRelativeProminence * value (so a small mesh ripple in a
//      wide lumen does not count, and a real fold in a narrow one does).
//   4. Non-maximum suppression per sector: strongest first, drop minima within
//      minSeparationMm of a kept one of the same sector.
// Fold spacing is then the distance between consecutive kept minima of the same sector
// (folds are staggered between sectors, so minima of different sectors are not paired),
// pooled over the sectors.
//
//   std::vector<FoldMinimum> m = FoldMinima(profile);
//   FoldSpacingSummary s = FoldSpacing(m, arc0, arc1);   // s.median, s.p25, s.p75, s.count
//
// Eigen and std only.
#include "RadiusProfile.h"

#include <limits>
#include <vector>

namespace colonmap {
namespace analysis {

struct FoldOptions {
  double smoothingMm = 2.0;            // Gaussian sigma along the arc
  double maxGapMm = 4.0;               // split the profile where no data lies within this
  double windowMm = 25.0;              // prominence search half-window
  double minProminenceMm = 1.0;        // absolute prominence threshold
  double minRelativeProminence = 0.05; // prominence threshold relative to the minimum's radius
  double minSeparationMm = 8.0;        // same-sector minima closer than this: keep the strongest
  bool perSector = true;               // false: use the all-angle median profile (sector -1)
};

struct FoldMinimum {
  double arc = 0.0;         // arc length of the minimum (bin centre)
  int sector = -1;          // angular sector, -1 for the all-angle profile
  double radius = 0.0;      // smoothed radius at the minimum
  double prominence = 0.0;  // see above
};

// The smoothed profile used by FoldMinima (column = sector, or one column for perSector = false).
Eigen::MatrixXd SmoothedProfile(const TubeProfile& profile, const FoldOptions& options = {});

// Kept minima, sorted by arc (then sector).
std::vector<FoldMinimum> FoldMinima(const TubeProfile& profile, const FoldOptions& options = {});

// Arc lengths of the kept minima (all sectors), sorted.
std::vector<double> FoldPositions(const TubeProfile& profile, const FoldOptions& options = {});

struct FoldSpacingSummary {
  double median = std::numeric_limits<double>::quiet_NaN();
  double p25 = std::numeric_limits<double>::quiet_NaN();
  double p75 = std::numeric_limits<double>::quiet_NaN();
  std::size_t count = 0;       // spacings (pairs of consecutive same-sector minima)
  std::size_t folds = 0;       // minima in the range
  std::vector<double> spacings;
};
// Spacings between consecutive minima of the same sector, both in [arc0, arc1).
FoldSpacingSummary FoldSpacing(const std::vector<FoldMinimum>& minima, double arc0, double arc1);

}  // namespace analysis
}  // namespace colonmap
