#include "Registration/SegmentRegistration.h"

#include "Core/Error.h"
#include "Flattening/BeltramiCoefficient.h"
#include "Surface/MeanCurvature.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <chrono>

namespace colonmap::registration {

namespace {

double Seconds(std::chrono::steady_clock::time_point& t0) {
  const auto now = std::chrono::steady_clock::now();
  const double s = std::chrono::duration<double>(now - t0).count();
  t0 = now;
  return s;
}

// (u, t): flat u and the relative arc length t in [0, 1] within the segment.
Eigen::MatrixXd ArcLengthCoordinates(const SegmentInput& s) {
  if (s.arcLength.size() != s.flat.uv.rows()) throw Error("the centerline method needs CenterlineArcLength on every vertex");
  // Robust ends (1st and 99th percentiles): a vertex whose nearest centerline point lies on a
  // neighbouring loop of the colon must not stretch the whole segment's scale.
  std::vector<double> a(s.arcLength.data(), s.arcLength.data() + s.arcLength.size());
  std::sort(a.begin(), a.end());
  const double a0 = a[a.size() / 100], a1 = a[a.size() - 1 - a.size() / 100];
  if (!(a1 > a0)) throw Error("CenterlineArcLength is constant over the segment");
  Eigen::MatrixXd ut(s.flat.uv.rows(), 2);
  ut.col(0) = s.flat.uv.col(0);
  ut.col(1) = ((s.arcLength.array() - a0) / (a1 - a0)).cwiseMax(0.0).cwiseMin(1.0);
  return ut;
}

}  // namespace

SegmentRegistration RegisterSegment(const SegmentInput& supine, const SegmentInput& prone, RegistrationMethod method,
                                    ProgressSink& progress) {
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
  if (method == RegistrationMethod::Conformal) {
    r.eta = FitRectangleAffine(supine.flat.uv, prone.flat.uv, shift);
    r.imageUV = r.eta.Apply(supine.flat.uv);
  } else {
    target.uv = ArcLengthCoordinates(prone);
    r.imageUV = ArcLengthCoordinates(supine);
    r.imageUV.col(0).array() += shift;
  }
  SubProgress forwardProgress(progress, 0.05, 0.5);
  r.forward = LocateInTarget(r.imageUV, target, forwardProgress);
  r.forward.uv = Interpolate(r.forward, prone.flat.F, prone.flat.uv);  // in prone FlatUV
  r.times.emplace_back("forward", Seconds(t0));

  // Inverse of the same map: the supine mesh laid out at its image points.
  source.uv = r.imageUV;
  source.period = period;
  SubProgress inverseProgress(progress, 0.5, 0.9);
  r.inverse = LocateInTarget(target.uv, source, inverseProgress);
  r.inverseSupineUV = Interpolate(r.inverse, supine.flat.F, supine.flat.uv);
  r.inverse.uv = r.inverseSupineUV;
  r.times.emplace_back("inverse", Seconds(t0));

  // One-to-one checks and distortion of the composed map.
  const Eigen::VectorXd area = flattening::SignedFlatAreas(r.imageUV, supine.flat.F);
  r.flatFlips = (area.array() <= 0.0).count();
  r.mu = SurfaceMapBeltrami(supine.flat.position, supine.flat.F, r.forward.position);
  const Eigen::MatrixXd proneNormals = surface::VertexNormals(prone.flat.position, prone.flat.F);
  const Eigen::MatrixXd imageNormalAtVertex = Interpolate(r.forward, prone.flat.F, proneNormals);
  for (Eigen::Index f = 0; f < supine.flat.F.rows(); ++f) {
    const Eigen::Vector3d a = r.forward.position.row(supine.flat.F(f, 0)), b = r.forward.position.row(supine.flat.F(f, 1)),
                          c = r.forward.position.row(supine.flat.F(f, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const Eigen::Vector3d ref = imageNormalAtVertex.row(supine.flat.F(f, 0)) + imageNormalAtVertex.row(supine.flat.F(f, 1)) +
                                imageNormalAtVertex.row(supine.flat.F(f, 2));
    if (n.dot(ref) <= 0.0) ++r.surfaceFlips;
  }
  r.times.emplace_back("distortion", Seconds(t0));
  progress.Report(1.0);
  return r;
}

}  // namespace colonmap::registration
