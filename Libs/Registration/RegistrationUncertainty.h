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
//   curv(x):  |mean curvature| averaged over about two rings of neighbours, x 10 mm, capped at 5:
//             fold crests and polyps (bumps) are where the wall differs most between the scans
//             and snapping to the other wall is least sure (issue 20: polyps had been covered
//             77% by a bound that held for 90% of wall points).
//   flex(x):  distance (mm along the segment) to the nearest end that is a flexure. Both scans'
//             segment ends are pinned to each other, so a flexure placed at slightly different
//             anatomy in the two scans moves every point near it (issue 20: on real-colon pairs
//             the errors above 20 mm lay within 50 mm of a flexure).
//   segment:  the alignment's 1 - path correlation (the curvature images disagree), the fraction
//             of matches the one-to-one guard dropped, matches per 100 mm of the segment, 1 - the
//             curvature images' correlation at their best shift, |log| of the segment's length
//             ratio between the scans, and how much the segment deformed between the scans (the
//             RMS of the map's 3D displacement left after the segment's best rigid motion,
//             RigidResidual.h): the colon's loops move against its fixed parts, and where a
//             segment bent and sheared more the wall slides in ways its shape does not show
//             (issue 20: per segment over the 42 pool pairs, log(1 + it / 10 mm) correlated 0.59
//             with the log of the segment's mean error, scripts/truth_shear.py; refitted with it, pairs with 85-95% of
//             their wall points covered rose from 32 to 35 of 42, held back by seed).
//   scale(x): the flat map's local scale (mm per flat unit: geometric mean of sqrt(3D area / flat
//             area) over the vertex's faces) over the segment's (MmPerFlatUnit). A flat error
//             becomes scale times more millimetres there: where the colon balloons (a wide
//             sigmoid), the conformal map shrinks it, and a small slip in the flat domain is a
//             large one on the wall (issue 20: on HuBMAP VHF pairs, log scale correlated 0.51 with
//             the log error, and the points above 20 mm that went unflagged had a scale of 2.4).
//   along(x): how far (mm along the colon) the registration puts x from where the centreline's
//             relative arc length alone would (both scans' segment ends are the same anatomy):
//             where they disagree by a fold spacing or more, one of them slipped (issue 20: the
//             tube at deformation 1.0 had whole segments one haustrum off, 20-27 mm, with bounds
//             of 4-9 mm; points whose two maps disagreed by over 20 mm were all more than 20 mm
//             off).
//   untrusted: 1 where RegistrationReliability.h does not trust the point (its segment rests on
//             nothing the scans share, or it lies near a suspect flexure), else 0. Known only
//             once every segment is registered: ApplyTrust sets it (issue 20: a fallback or a
//             mis-paired segment must widen the bound, not only mark the point).
// Combined by two fixed log-linear models of the same inputs (UncertaintyFeatures; coefficients
// in RegistrationUncertainty.cxx, fitted by scripts/fit_uncertainty.py on phantom and real-colon
// pairs: docs/accuracy.md gives the data, the fit and the held-back figures):
//   log sigma(x) = c . UncertaintyFeatures(x),  sigma the predicted median error (least squares);
//   log bound90(x) = b . UncertaintyFeatures(x),  the 90% bound (linear quantile regression), so
// that an input which spreads the errors more than it raises their median widens the bound
// more (one factor on sigma for every point held on some pairs and not on others). Eigen in and out.
#include "Registration/SurfaceMap.h"

#include <Eigen/Core>

#include <array>
#include <vector>

namespace colonmap::registration {

struct ConstraintPoint {
  Eigen::Vector2d uv{0, 0};            // supine flat position
  Eigen::Vector2d displacement{0, 0};  // wanted h there (flat units)
  int group = 0;                       // the match it belongs to
};

struct SegmentEvidence {
  double pathCorrelation = 1.0;     // CurvatureWarp::pathCorrelation (1 when no warp)
  double droppedFraction = 0.0;     // guard-dropped matches / matches before the guard
  double matchesPer100mm = 0.0;     // kept matches per 100 mm of segment length (EstimateUncertainty sets it)
  double curvatureAgreement = 1.0;  // correlation of the curvature images at their best shift (1 without images)
  double lengthMismatch = 0.0;      // |log(supine length / prone length)| of the segment
  double deformationMm = 0.0;       // RMS of the 3D displacement beyond the segment's best rigid motion
  std::array<bool, 2> flexureAtEnd{false, false};  // its v-min (anal) and v-max ends are flexures, not colon tips
};

// Distance used for "no flexure end" (a segment between the two tips of the colon).
constexpr double kNoFlexureMm = 1000.0;

struct UncertaintyComponents {
  Eigen::VectorXd loo, nearMm, correctionMm, dilatation;  // per vertex
  Eigen::VectorXd endMm[2];  // distance along the segment (mm) to its v-min and its v-max end
  Eigen::VectorXd flexureMm; // to the nearest end that is a flexure (kNoFlexureMm when none)
  Eigen::VectorXd curvature; // the curv input above (0 without mean curvature)
  Eigen::VectorXd scale;     // the scale input above (1 on a map of even scale)
  Eigen::VectorXd alongMm;   // the along input above (0 without arc lengths)
};

// One point's inputs (the per-vertex components at one vertex).
struct PointEvidence {
  double loo = 0.0, nearMm = 0.0, correctionMm = 0.0, dilatation = 1.0, flexureMm = kNoFlexureMm, curvature = 0.0;
  bool trusted = true;
  double scale = 1.0;
  double alongMm = 0.0;
};

struct VertexUncertainty {
  UncertaintyComponents components;
  Eigen::VectorXd median;  // sigma per vertex (mm): the predicted median error
  Eigen::VectorXd bound90; // the 90% bound (mm)
  SegmentEvidence segment; // as used (matchesPer100mm filled in)
  double mmPerFlatUnit = 1.0;
};

// The segment's scale (mm per flat unit: the flat map is near conformal, so one per segment, from
// the areas) and its length along v (mm).
double MmPerFlatUnit(const FlatSegment& flat);
double FlatLengthMm(const FlatSegment& flat);

// flat: the supine segment (uv, F, position, period); h: n x 2 correction (zero rows when none);
// K: per-face dilatation (m values, +inf allowed); constraints: the kept ones; meanCurvature: per
// vertex (1/mm; empty: no curvature input); alongMm: per vertex (empty: 0).
VertexUncertainty EstimateUncertainty(const FlatSegment& flat, const Eigen::MatrixXd& h, const Eigen::VectorXd& K,
                                      const std::vector<ConstraintPoint>& constraints, const SegmentEvidence& segment,
                                      const Eigen::VectorXd& meanCurvature = Eigen::VectorXd(),
                                      const Eigen::VectorXd& alongMm = Eigen::VectorXd(), int neighbours = 6);

// The model's inputs at one point, in the order of its coefficients (1 first): 1, log(1 + loo),
// log(1 + near / 10 mm), log(1 + corr), log K (K >= 1, +inf as 10), 1 - pathCorrelation,
// droppedFraction, 1 / (1 + matchesPer100mm), exp(-flex / 30 mm), 1 - curvatureAgreement,
// lengthMismatch, curv, untrusted, log scale (clamped to [-2, 3]), log(1 + along / 10 mm),
// log(1 + deformation / 10 mm). scripts/fit_uncertainty.py computes the same.
constexpr int kUncertaintyFeatures = 16;
Eigen::Matrix<double, kUncertaintyFeatures, 1> UncertaintyFeatures(const PointEvidence& point, const SegmentEvidence& segment);

// The model alone (for tests and for documenting it): sigma from the components of one point.
double UncertaintyMedian(const PointEvidence& point, const SegmentEvidence& segment);
double UncertaintyBound90(const PointEvidence& point, const SegmentEvidence& segment);

// Recomputes median and bound90 where trusted (per vertex, 0/1) is 0: the model's untrusted input
// (EstimateUncertainty assumes every point trusted).
void ApplyTrust(VertexUncertainty& uncertainty, const Eigen::VectorXd& trusted);

}  // namespace colonmap::registration
