#pragma once
// Registration of one colon segment, supine -> prone, from the two flat maps (DESIGN §2.4):
//   Conformal (the "conformal map only" baseline of Zeng et al. 2010):
//     Phi = phi2^-1 o eta o phi1, eta the affine rectangle map (RectangleAffine.h): v scaled by
//     the length ratio, u shifted cyclically (0 when both scans were cut along the same taenia;
//     else the shift that best correlates the two curvature images around the colon).
//   Centerline (the centerline arc-length baseline the paper compares against): a point goes to
//     the prone point with the same relative centerline arc length in its segment (t in [0, 1]
//     from the vertices' CenterlineArcLength between its 1st and 99th percentile over the segment) and the same u around the colon (the flat u, i.e.
//     the angular position measured from the cut taenia), without curvature alignment.
//   Harmonic (DESIGN §2.4, issue 7): an initial map W (the curvature images aligned along and
//     around the colon, CurvatureAlignment.h; eta when harmonic.curvatureAlignment is off), then
//     fold features of both scans (FoldFeatures.h), matched after W (FeatureMatching.h), and the
//     harmonic correction h with the matched features' centroids and principal-axis ends as
//     constraints (HarmonicCorrection.h): Phi = phi2^-1 o (W o phi1 + h), never folded (W is
//     one-to-one; the correction's one-to-one guard).
// The inverse (prone -> supine) inverts the same map: prone vertices are located in the supine
// mesh laid out at its image coordinates eta(phi1), not registered independently. Eigen and
// Core in and out.
#include "Core/Cancel.h"
#include "Core/Volume.h"
#include "Registration/CurvatureAlignment.h"
#include "Registration/FeatureMatching.h"
#include "Registration/FoldFeatures.h"
#include "Registration/HarmonicCorrection.h"
#include "Registration/RectangleAffine.h"
#include "Registration/RegistrationUncertainty.h"
#include "Registration/SurfaceMap.h"

#include <array>
#include <string>
#include <utility>
#include <vector>

namespace colonmap::registration {

enum class RegistrationMethod { Conformal, Centerline, Harmonic };

// Options of the Harmonic method.
struct HarmonicOptions {
  FoldOptions folds;
  MatchOptions matching;
  HarmonicCorrectionOptions correction;
  bool axisEnds = true;  // constrain the principal-axis end points too (else centroids only)
  int passes = 1;        // matching + correction rounds (>= 1); later ones match after eta + h
  // The initial map: the curvature-image warp (CurvatureAlignment.h) in place of eta.
  bool curvatureAlignment = true;
  AlignmentOptions alignment;
};

struct SegmentInput {
  FlatSegment flat;               // FlatUV, faces, Position3D, period
  Eigen::VectorXd arcLength;      // CenterlineArcLength per vertex (Centerline method only)
  const Volume<float>* curvature = nullptr;  // curvature image (optional: no shift correlation)
  std::string cutTaenia;          // name of the cut taenia ("" unknown)
  Eigen::VectorXd meanCurvature;  // MeanCurvature per vertex (Harmonic method only)
  std::array<bool, 2> flexureAtEnd{true, true};  // v-min (anal) and v-max ends are flexures, not colon tips
};

struct SegmentRegistration {
  RectangleAffine eta;            // Conformal: the affine map; Centerline: identity
  CurvatureWarp warp;             // Harmonic with curvatureAlignment: the initial map W
  bool warped = false;            // W replaces eta as the initial map
  CyclicShift correlation;        // of the curvature images (when both are given)
  bool shiftFromCorrelation = false;  // the applied shift is the correlation's (cuts differ)
  Eigen::MatrixXd imageUV;        // supine vertices' query points in the prone flat domain
  VertexImages forward;           // supine vertex -> prone face, bary, uv, position
  VertexImages inverse;           // prone vertex -> supine face, bary, position
  Eigen::MatrixXd inverseSupineUV;  // prone vertices' images in supine FlatUV
  Eigen::VectorXcd mu;            // per supine face, of the 3D -> 3D map
  long flatFlips = 0;             // supine faces whose image in the prone flat domain is reversed
  long surfaceFlips = 0;          // supine faces whose 3D image faces against the prone surface
  int repairRounds = 0;           // Harmonic: local relaxations of the image around reversed faces
  long repairedVertices = 0;      // vertices moved by them (summed over rounds)
  long surfaceRepairedVertices = 0;  // Harmonic: image vertices moved off 3D reversals (SurfaceFlipRepair.h)
  // Harmonic method: folds of both scans, the matches kept by the one-to-one guard, the correction.
  std::vector<FoldFeature> supineFolds, proneFolds;
  std::vector<FeatureMatch> matches;  // after the guard (dropped ones removed)
  int matchesBeforeGuard = 0;
  HarmonicCorrectionResult correction;
  std::vector<ConstraintPoint> constraints;  // Harmonic: the constraints of the kept matches
  VertexUncertainty uncertainty;             // per supine vertex (RegistrationUncertainty.h)
  std::vector<std::pair<std::string, double>> times;  // seconds: shift, forward, inverse, distortion
};

// Throws colonmap::Error (a sentence, no input name) for inconsistent inputs (e.g. the Centerline
// method without arc lengths). progress: Report(0..1), may throw Cancelled.
SegmentRegistration RegisterSegment(const SegmentInput& supine, const SegmentInput& prone, RegistrationMethod method,
                                    ProgressSink& progress, const HarmonicOptions& harmonic = {});

}  // namespace colonmap::registration
