#pragma once
// Lumen radius profile of a tube (the colon) along its midline, libigl style: wall points are
// assigned to the arc length of their nearest midline point (exact, ProjectToMidline), binned
// along the midline, and each bin's radius is the median distance of its points to the
// midline, over all angles and per angular sector (rotation-minimising frame, sector k covers
// angles [k, k + 1) * 2 pi / sectors).
//
//   Eigen::MatrixXd P = SampleSurface(wall.V, wall.F, 1.0);      // area-uniform wall points
//   TubeProfile p = RadiusProfile(P, midline, 1.0);              // 1 mm bins, 8 sectors
//   RadiusSummary a = SummarizeRadius(p, 0.0, 300.0);            // median radius over an arc range
//
// The median makes a bin robust to the few wall points that project onto the wrong stretch
// of midline where loops of the colon touch, to polyps and, over all angles, to folds (which
// cover a sector only); the per-sector profiles keep the folds (see FoldPositions.h).
// Units are those of the inputs (mm for ColonMap). Eigen and std only.
#include "MidlineProjection.h"

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace colonmap {
namespace analysis {

struct TubeProfile {
  double binMm = 1.0;     // bin k covers arc [k, k + 1) * binMm
  double length = 0.0;    // midline length (the last bin may be partial)
  int sectors = 0;
  Eigen::VectorXd arc;    // bin centres (k + 0.5) * binMm, nBins = ceil(length / binMm)
  Eigen::VectorXd radius; // median distance over all angles; NaN if fewer than minCount points
  Eigen::VectorXi count;  // wall points per bin
  Eigen::MatrixXd sectorRadius;  // nBins x sectors medians; NaN if fewer than minCount points
  Eigen::MatrixXi sectorCount;   // nBins x sectors
  Eigen::Index excluded = 0;     // wall points without an arc (past the ends, or too far)

  Eigen::Index NumberOfBins() const { return arc.size(); }
};

struct ProfileOptions {
  int sectors = 8;       // angular sectors (>= 1)
  int minCount = 3;      // fewer points than this in a bin (or bin-sector): no value (NaN)
  ProjectionOptions projection;  // end exclusion, maximum distance, grid, frame start
};

// wallPoints: n x 3; midline: m x 3 polyline (m >= 2), ordered along the tube.
TubeProfile RadiusProfile(const Eigen::MatrixXd& wallPoints, const Eigen::MatrixXd& midline, double binMm,
                          const ProfileOptions& options = {});
// The same from a projection already computed (arc, distance, angle per point) on a midline
// of the given length.
TubeProfile RadiusProfile(const MidlineProjection& projection, double midlineLength, double binMm,
                          const ProfileOptions& options = {});

struct RadiusSummary {
  double median = std::numeric_limits<double>::quiet_NaN();  // median over bins of the bin radius
  double p10 = std::numeric_limits<double>::quiet_NaN();     // 10th / 90th percentile over bins
  double p90 = std::numeric_limits<double>::quiet_NaN();
  Eigen::Index bins = 0;  // bins with a value whose centre lies in the range
};
// Over the bins whose centre lies in [arc0, arc1): each bin counts once, so the summary is
// per length of colon, not per wall point (independent of mesh density and of how much wall a
// wide lumen has).
RadiusSummary SummarizeRadius(const TubeProfile& profile, double arc0, double arc1);

// Linear-interpolated quantile q in [0, 1] of the values (NaN if empty); takes a copy.
double Quantile(std::vector<double> values, double q);

}  // namespace analysis
}  // namespace colonmap
