#include "Registration/SegmentRegistration.h"

#include "Core/Error.h"
#include "Flattening/BeltramiCoefficient.h"
#include "Registration/FlatLocator.h"
#include "Registration/FlipRepair.h"
#include "Registration/RigidResidual.h"
#include "Registration/SurfaceFlipRepair.h"
#include "Surface/MeanCurvature.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>
#include <cmath>

namespace colonmap::registration {

namespace {

double Seconds(std::chrono::steady_clock::time_point& t0) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t0).count();
  t0 = now;
  return s;
}

// The segment's CenterlineArcLength span (arcLength given on every vertex): its 1st and 99th
// percentiles (robust ends: a vertex whose nearest centerline point lies on a neighbouring loop
// of the colon must not stretch the whole segment's scale).
std::pair<double, double> ArcSpan(const SegmentInput& s) {
  std::vector<double> a(s.arcLength.data(), s.arcLength.data() + s.arcLength.size());
  std::sort(a.begin(), a.end());
  return {a[a.size() / 100], a[a.size() - 1 - a.size() / 100]};
}

bool HasArcLengths(const SegmentInput& s) { return s.arcLength.size() > 0 && s.arcLength.size() == s.flat.uv.rows(); }

// (u, t): flat u and the relative arc length t in [0, 1] within the segment.
Eigen::MatrixXd ArcLengthCoordinates(const SegmentInput& s) {
  if (!HasArcLengths(s)) throw Error("the centerline method needs CenterlineArcLength on every vertex");
  const auto [a0, a1] = ArcSpan(s);
  if (!(a1 > a0)) throw Error("CenterlineArcLength is constant over the segment");
  Eigen::MatrixXd ut(s.flat.uv.rows(), 2);
  ut.col(0) = s.flat.uv.col(0);
  ut.col(1) = ((s.arcLength.array() - a0) / (a1 - a0)).cwiseMax(0.0).cwiseMin(1.0);
  return ut;
}

// Per supine vertex, how far (mm along the colon) its image lies from where the centreline arc
// length alone would put it (the same relative arc length in the prone segment); empty without
// usable arc lengths on both.
Eigen::VectorXd AlongDisagreementMm(const SegmentInput& supine, const SegmentInput& prone, const VertexImages& forward) {
  if (!HasArcLengths(supine) || !HasArcLengths(prone)) return Eigen::VectorXd();
  const auto [s0, s1] = ArcSpan(supine);
  const auto [p0, p1] = ArcSpan(prone);
  if (!(s1 > s0) || !(p1 > p0) || !supine.arcLength.allFinite() || !prone.arcLength.allFinite()) return Eigen::VectorXd();
  const Eigen::VectorXd imageArc = Interpolate(forward, prone.flat.F, prone.arcLength).col(0);
  const Eigen::ArrayXd ts = (supine.arcLength.array() - s0) / (s1 - s0), tp = (imageArc.array() - p0) / (p1 - p0);
  return ((tp - ts).abs() * 0.5 * ((s1 - s0) + (p1 - p0))).matrix();
}

// The Harmonic method's steps after eta: folds, matches, constraints, h; r.imageUV += h.
void CorrectHarmonic(const SegmentInput& supine, const SegmentInput& prone, const HarmonicOptions& o, SegmentRegistration& r,
                     ProgressSink& progress) {
  if (supine.meanCurvature.size() != supine.flat.uv.rows() || prone.meanCurvature.size() != prone.flat.uv.rows())
    throw Error("the harmonic method needs MeanCurvature on every vertex");
  r.supineFolds = DetectFolds(supine.flat, supine.meanCurvature, o.folds);
  r.proneFolds = DetectFolds(prone.flat, prone.meanCurvature, o.folds);
  progress.Report(0.2);
  const double period = prone.flat.period;
  const FlatTriangleLocator locator(supine.flat.uv, supine.flat.F, supine.flat.period);
  auto nearestVertex = [&](const Eigen::Vector2d& p) {
    const FlatHit h = locator.Locate(p);
    Eigen::Index k = 0;
    h.bary.maxCoeff(&k);
    return supine.flat.F(h.face, static_cast<int>(k));
  };
  // The initial map: the curvature-image warp when it was computed, else the affine eta.
  const auto initial = [&](const Eigen::Vector2d& p) { return r.warped ? r.warp.Apply(p) : r.eta.Apply(p); };
  const Eigen::MatrixXd etaUV = r.imageUV;
  Eigen::MatrixXd predicted0(r.supineFolds.size(), 2);
  for (std::size_t i = 0; i < r.supineFolds.size(); ++i)
    predicted0.row(static_cast<Eigen::Index>(i)) = initial(r.supineFolds[i].centroid).transpose();
  std::vector<FeatureMatch> matches = MatchFolds(r.supineFolds, r.proneFolds, predicted0, period, o.matching);
  // Passes: match after eta, correct, then match again after eta + h (the first correction
  // brings more folds within the search radius), correct again from eta.
  for (int pass = 0; pass < o.passes; ++pass) {
    if (pass > 0) {
      Eigen::MatrixXd predicted(r.supineFolds.size(), 2);
      for (std::size_t i = 0; i < r.supineFolds.size(); ++i) {
        const FlatHit h = locator.Locate(r.supineFolds[i].centroid);
        Eigen::Vector2d q(0, 0);
        for (int k = 0; k < 3; ++k) q += h.bary(k) * r.correction.imageUV.row(supine.flat.F(h.face, k)).transpose();
        predicted.row(static_cast<Eigen::Index>(i)) = q.transpose();
      }
      matches = MatchFolds(r.supineFolds, r.proneFolds, predicted, period, o.matching);
    }
    r.matchesBeforeGuard = static_cast<int>(matches.size());
    // Constraints: each match's centroid, and its axis ends paired the way that keeps them closest.
    std::vector<FlatConstraint> constraints;
    for (int m = 0; m < static_cast<int>(matches.size()); ++m) {
      const FoldFeature& a = r.supineFolds[matches[m].supine];
      const FoldFeature& b = r.proneFolds[matches[m].prone];
      std::vector<std::pair<Eigen::Vector2d, Eigen::Vector2d>> pairs{{a.centroid, b.centroid}};
      if (o.axisEnds) {
        const auto d = [&](const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
          return PeriodicDifference(q, initial(p), period).norm();
        };
        const bool same = d(a.ends[0], b.ends[0]) + d(a.ends[1], b.ends[1]) <= d(a.ends[0], b.ends[1]) + d(a.ends[1], b.ends[0]);
        pairs.emplace_back(a.ends[0], same ? b.ends[0] : b.ends[1]);
        pairs.emplace_back(a.ends[1], same ? b.ends[1] : b.ends[0]);
      }
      for (const auto& [p, q] : pairs)
        constraints.push_back({nearestVertex(p), PeriodicDifference(q, initial(p), period), m});
    }
    SubProgress sub(progress, 0.3 + 0.7 * pass / o.passes, 0.3 + 0.7 * (pass + 1) / o.passes);
    r.correction = SolveHarmonicCorrection(supine.flat, etaUV, constraints, o.correction, sub);
    r.constraints.clear();
    for (const FlatConstraint& c : constraints)
      if (!std::binary_search(r.correction.droppedGroups.begin(), r.correction.droppedGroups.end(), c.group))
        r.constraints.push_back({supine.flat.uv.row(c.vertex).transpose(), c.displacement, c.group});
  }
  r.imageUV = r.correction.imageUV;
  for (int m = 0; m < static_cast<int>(matches.size()); ++m)
    if (!std::binary_search(r.correction.droppedGroups.begin(), r.correction.droppedGroups.end(), m))
      r.matches.push_back(matches[m]);
}

}  // namespace

SegmentRegistration RegisterSegment(const SegmentInput& supine, const SegmentInput& prone, RegistrationMethod method,
                                    ProgressSink& progress, const HarmonicOptions& harmonic) {
  SegmentRegistration r;
  auto t0 = std::chrono::steady_clock::now();
  if (supine.curvature && prone.curvature) r.correlation = CyclicShiftByCorrelation(*supine.curvature, *prone.curvature);
  const double period = prone.flat.period > 0 ? prone.flat.period : 1.0;
  // Same cut taenia: the cut lines are the same anatomy, so no shift; different (or unknown)
  // cuts: the curvature correlation's shift, in units of the width.
  r.shiftFromCorrelation = supine.cutTaenia.empty() || supine.cutTaenia != prone.cutTaenia;
  const double shift = r.shiftFromCorrelation ? r.correlation.shift * period : 0.0;
  r.times.emplace_back("shift", Seconds(t0));
  progress.Report(0.05);

  FlatSegment target = prone.flat, source = supine.flat;
  if (method == RegistrationMethod::Conformal || method == RegistrationMethod::Harmonic) {
    r.eta = FitRectangleAffine(supine.flat.uv, prone.flat.uv, shift);
    r.imageUV = r.eta.Apply(supine.flat.uv);
    if (method == RegistrationMethod::Harmonic && harmonic.curvatureAlignment) {
      if (supine.meanCurvature.size() != supine.flat.uv.rows() || prone.meanCurvature.size() != prone.flat.uv.rows())
        throw Error("the harmonic method needs MeanCurvature on every vertex");
      SubProgress sub(progress, 0.05, 0.1);
      r.warp = AlignCurvatureImages(supine.flat, supine.meanCurvature, prone.flat, prone.meanCurvature, harmonic.alignment, sub);
      r.warped = r.warp.valid;  // else eta (one-to-one on flip-free flat maps)
      if (r.warped) r.imageUV = r.warp.Apply(supine.flat.uv);
      r.times.emplace_back("alignment", Seconds(t0));
    }
  } else {
    target.uv = ArcLengthCoordinates(prone);
    r.imageUV = ArcLengthCoordinates(supine);
    r.imageUV.col(0).array() += shift;
  }
  if (method == RegistrationMethod::Harmonic) {
    SubProgress sub(progress, 0.1, 0.25);
    CorrectHarmonic(supine, prone, harmonic, r, sub);
    r.times.emplace_back("features+matching+harmonic", Seconds(t0));
  }
  // The Harmonic method's last one-to-one guard: a face whose 3D image faces against the prone
  // surface (possible where a sharply stretched flat face spans a fold) halves h and relocates;
  // after 6 halvings h = 0 (the affine map, one-to-one on flip-free flat maps).
  const Eigen::MatrixXd etaUV = method != RegistrationMethod::Harmonic ? Eigen::MatrixXd()
                                : r.warped ? r.warp.Apply(supine.flat.uv) : r.eta.Apply(supine.flat.uv);
  int repairs = 0, surfaceMoves = 0;
  for (;;) {
    r.flatFlips = r.surfaceFlips = 0;
    SubProgress forwardProgress(progress, 0.25, 0.55);
    r.forward = LocateInTarget(r.imageUV, target, forwardProgress);
    r.forward.uv = Interpolate(r.forward, prone.flat.F, prone.flat.uv);  // in prone FlatUV
    r.times.emplace_back("forward", Seconds(t0));

    // Inverse of the same map: the supine mesh laid out at its image points.
    source.uv = r.imageUV;
    source.period = period;
    SubProgress inverseProgress(progress, 0.55, 0.9);
    r.inverse = LocateInTarget(target.uv, source, inverseProgress);
    r.inverseSupineUV = Interpolate(r.inverse, supine.flat.F, supine.flat.uv);
    r.inverse.uv = r.inverseSupineUV;
    r.times.emplace_back("inverse", Seconds(t0));

    // One-to-one checks and distortion of the composed map.
    const Eigen::VectorXd area = flattening::SignedFlatAreas(r.imageUV, supine.flat.F);
    std::vector<Eigen::Index> bad;
    r.mu = FlatFrameBeltrami(supine.flat.position, supine.flat.uv, supine.flat.F, r.forward.position);
    const Eigen::MatrixXd proneNormals = surface::VertexNormals(prone.flat.position, prone.flat.F);
    const Eigen::MatrixXd imageNormalAtVertex = Interpolate(r.forward, prone.flat.F, proneNormals);
    for (Eigen::Index f = 0; f < supine.flat.F.rows(); ++f) {
      const bool flat = area(f) <= 0.0, surface = !ImageFacesAlongSurface(supine.flat.F, f, r.forward.position, imageNormalAtVertex);
      r.flatFlips += flat;
      r.surfaceFlips += surface;
      if (flat || surface) bad.push_back(f);
    }
    if (method != RegistrationMethod::Harmonic || bad.empty()) break;
    // Only 3D reversals (a straight image triangle across target triangles of very different
    // shape): move single image vertices with the 3D check in view (SurfaceFlipRepair.h) before
    // anything that changes the map more widely.
    if (r.flatFlips == 0 && surfaceMoves < 3) {
      const int moved = RepairSurfaceFlips(r.imageUV, supine.flat.F, prone.flat, proneNormals, r.forward.position,
                                           imageNormalAtVertex, bad);
      r.surfaceRepairedVertices += moved;
      ++surfaceMoves;
      if (moved > 0) continue;
    }
    // Reversed faces (inherited from a flattening's own reversed triangles, or made by h): first
    // relax the image locally, on growing patches; then halve h and try again.
    if (repairs < 4) {
      r.repairedVertices += RelaxAroundFaces(r.imageUV, supine.flat.F, bad, 1 + repairs);
      ++repairs;
      ++r.repairRounds;
      continue;
    }
    if (r.correction.scale == 0.0) break;
    repairs = surfaceMoves = 0;
    const bool halve = r.correction.surfaceRetries < 6;  // then h = 0: the initial map alone
    r.correction.scale = halve ? 0.5 * r.correction.scale : 0.0;
    r.correction.h *= halve ? 0.5 : 0.0;
    r.imageUV = etaUV + r.correction.h;
    ++r.correction.surfaceRetries;
  }
  r.times.emplace_back("distortion", Seconds(t0));
  // Per-vertex uncertainty from the map's own evidence (the correction after any damping).
  SegmentEvidence evidence;
  evidence.pathCorrelation = r.warped ? r.warp.pathCorrelation : 1.0;
  evidence.droppedFraction =
      r.matchesBeforeGuard > 0 ? 1.0 - static_cast<double>(r.matches.size()) / r.matchesBeforeGuard : 0.0;
  evidence.curvatureAgreement = supine.curvature && prone.curvature ? r.correlation.correlation : 1.0;
  const double supineLength = FlatLengthMm(supine.flat), proneLength = FlatLengthMm(prone.flat);
  evidence.lengthMismatch = supineLength > 0 && proneLength > 0 ? std::abs(std::log(supineLength / proneLength)) : 0.0;
  evidence.flexureAtEnd = supine.flexureAtEnd;
  evidence.deformationMm = RigidResidualRms(supine.flat.position, r.forward.position);
  const Eigen::MatrixXd h = method == RegistrationMethod::Harmonic && r.correction.h.rows() == supine.flat.uv.rows()
                                ? Eigen::MatrixXd(r.imageUV - etaUV)
                                : Eigen::MatrixXd(Eigen::MatrixXd::Zero(supine.flat.uv.rows(), 2));
  r.uncertainty = EstimateUncertainty(supine.flat, h, Dilatation(r.mu), r.constraints, evidence, supine.meanCurvature,
                                      AlongDisagreementMm(supine, prone, r.forward));
  r.times.emplace_back("uncertainty", Seconds(t0));
  progress.Report(1.0);
  return r;
}

}  // namespace colonmap::registration
