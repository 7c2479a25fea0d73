#pragma once
// Per-vertex uncertainty of a segment registration (issue 7, ColonTransferPoints), in mm, from
// what the registration itself shows (no truth). Why these terms: between matched folds the map
// is an interpolation (the harmonic correction), so its error there is about how badly the
// interpolation would have predicted a match it had not seen, and grows with the distance to the
// nearest match; where the initial map needed a large correction it was wrong there and the
// correction's shape between the matches is a guess.
//   loo(x):   leave-one-out residuals of the matches near x. For each kept match k (its centroid
//             and axis-end constraints form one group), the displacement its neighbours predict
//             (inverse-distance weighted mean of the nearest `neighbours` constraints of other
//             groups) minus its own, |.| in mm; at x the Gaussian-weighted RMS (sigma = the
//             distance to the `neighbours`-th nearest constraint) of those residuals.
//   near(x):  distance (mm) from x to the nearest kept constraint.
//   corr(x):  |h(x)| in mm, the size of the harmonic correction.
//   K(x):     the map's dilatation (mean over the vertex's faces).
//   segment:  the alignment's 1 - path correlation (the curvature images disagree), the fraction
//             of matches the one-to-one guard dropped, matches per 100 mm of the segment.
// Combined by a fixed model (coefficients in RegistrationUncertainty.cxx, fitted on the phantom:
// see the README's ColonTransferPoints section for the data, the fit and the held-out figures):
//   log sigma(x) = c0 + c1 log(1 + loo) + c2 log(1 + near / 10 mm) + c3 log(1 + corr)
//                  + c4 log K + c5 (1 - pathCorrelation) + c6 dropped + c7 / (1 + matchesPer100mm),
// sigma the predicted median error; a `quantile` bound is sigma * exp(z_q s) with s the spread of
// the fit's log residuals (the 90% bound: uncertainty90). Eigen in and out.
#include "Registration/SurfaceMap.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::registration {

struct ConstraintPoint {
  Eigen::Vector2d uv{0, 0};            // supine flat position
  Eigen::Vector2d displacement{0, 0};  // wanted h there (flat units)
  int group = 0;                       // the match it belongs to
};

struct SegmentEvidence {
  double pathCorrelation = 1.0;  // CurvatureWarp::pathCorrelation (1 when no warp)
  double droppedFraction = 0.0;  // guard-dropped matches / matches before the guard
  double matchesPer100mm = 0.0;  // kept matches per 100 mm of segment length (EstimateUncertainty sets it)
};

struct UncertaintyComponents {
  Eigen::VectorXd loo, nearMm, correctionMm, dilatation;  // per vertex
};

struct VertexUncertainty {
  UncertaintyComponents components;
  Eigen::VectorXd median;  // sigma per vertex (mm): the predicted median error
  Eigen::VectorXd bound90; // the 90% bound (mm)
  SegmentEvidence segment; // as used (matchesPer100mm filled in)
  double mmPerFlatUnit = 1.0;
};

// flat: the supine segment (uv, F, position, period); h: n x 2 correction (zero rows when none);
// K: per-face dilatation (m values, +inf allowed); constraints: the kept ones.
VertexUncertainty EstimateUncertainty(const FlatSegment& flat, const Eigen::MatrixXd& h, const Eigen::VectorXd& K,
                                      const std::vector<ConstraintPoint>& constraints, const SegmentEvidence& segment,
                                      int neighbours = 6);

// The model alone (for tests and for documenting it): sigma from the components of one point.
double UncertaintyMedian(double loo, double nearMm, double correctionMm, double dilatation, const SegmentEvidence& segment);
double UncertaintyBound90(double median);

}  // namespace colonmap::registration
