#include "Landmarks/CentrelineAlignment.h"

#include "Analysis/DynamicTimeWarping.h"
#include "Analysis/Interpolate.h"
#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "Landmarks/Centerline.h"

#include <algorithm>
#include <cmath>

namespace colonmap::landmarks {

namespace {

// Unit direction of travel at each sample of an evenly spaced polyline (chord over +-w samples).
Eigen::MatrixXd Directions(const Eigen::MatrixXd& P, int w) {
  const Eigen::Index n = P.rows();
  Eigen::MatrixXd t(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector3d d = P.row(std::min<Eigen::Index>(n - 1, i + w)) - P.row(std::max<Eigen::Index>(0, i - w));
    const double len = d.norm();
    t.row(i) = len > 0 ? Eigen::RowVector3d(d / len) : Eigen::RowVector3d::Zero();
  }
  return t;
}

}  // namespace

CentrelineAlignment::CentrelineAlignment(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b,
                                         const CentrelineAlignmentOptions& o) {
  if (a.rows() < 2 || b.rows() < 2) throw Error("centreline alignment: each centreline needs two points");
  const Eigen::MatrixXd A = ResamplePolyline(a, o.stepMm), B = ResamplePolyline(b, o.stepMm);
  arcA_ = analysis::ArcLength(A);
  arcB_ = analysis::ArcLength(B);
  const int w = std::max(1, static_cast<int>(std::round(o.tangentMm / o.stepMm)));
  analysis::WarpingOptions wo;
  wo.band = o.band;
  wo.stepPenalty = o.stepPenalty;
  const analysis::Warping warp = analysis::WarpSequences(Directions(A, w), Directions(B, w), wo);
  meanCost = warp.cost / std::max(1, warp.length);
  const auto toArc = [](const Eigen::VectorXd& arcs, double index) {
    const Eigen::Index i = std::clamp<Eigen::Index>(static_cast<Eigen::Index>(index), 0, arcs.size() - 1);
    const Eigen::Index j = std::min<Eigen::Index>(i + 1, arcs.size() - 1);
    return arcs(i) + (index - static_cast<double>(i)) * (arcs(j) - arcs(i));
  };
  matchedB_.resize(arcA_.size());
  matchedA_.resize(arcB_.size());
  for (Eigen::Index i = 0; i < arcA_.size(); ++i) matchedB_(i) = toArc(arcB_, warp.matchedInB(i));
  for (Eigen::Index j = 0; j < arcB_.size(); ++j) matchedA_(j) = toArc(arcA_, warp.matchedInA(j));
  if (o.smoothMm > 0) SpreadJumps(o.smoothMm / o.stepMm);
}

void CentrelineAlignment::SpreadJumps(double sigmaSamples) {
  const double ratio = arcB_(arcB_.size() - 1) / std::max(1e-12, arcA_(arcA_.size() - 1));
  const Eigen::VectorXd offset = SmoothPolyline(matchedB_ - ratio * arcA_, sigmaSamples);
  matchedB_ = ratio * arcA_ + offset;
  for (Eigen::Index i = 1; i < matchedB_.size(); ++i) matchedB_(i) = std::max(matchedB_(i), matchedB_(i - 1));
  // b -> a from the same path, so the two directions stay each other's inverse.
  for (Eigen::Index j = 0; j < arcB_.size(); ++j) matchedA_(j) = analysis::InterpolateLinear(matchedB_, arcA_, arcB_(j));
}

ArcMap::ArcMap(const Eigen::MatrixXd& from, const Eigen::MatrixXd& onto, double stepMm) {
  const Eigen::MatrixXd F = ResamplePolyline(from, stepMm);
  from_ = analysis::ArcLength(F);
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  onto_ = analysis::ProjectToMidline(F, onto, po).arc;
  for (Eigen::Index i = 1; i < onto_.size(); ++i) onto_(i) = std::max(onto_(i), onto_(i - 1));
}

double ArcMap::Forward(double arcFrom) const { return analysis::InterpolateLinear(from_, onto_, arcFrom); }
double ArcMap::Backward(double arcOnto) const { return analysis::InterpolateLinear(onto_, from_, arcOnto); }

CentrelineAlignment CentrelineAlignment::InArcsOf(const ArcMap& onA, const ArcMap& onB) const {
  CentrelineAlignment r;
  r.meanCost = meanCost;
  r.arcA_ = onA.FromArcs();
  r.arcB_ = onB.FromArcs();
  r.matchedB_.resize(r.arcA_.size());
  r.matchedA_.resize(r.arcB_.size());
  for (Eigen::Index i = 0; i < r.arcA_.size(); ++i) r.matchedB_(i) = onB.Backward(AToB(onA.Forward(r.arcA_(i))));
  for (Eigen::Index j = 0; j < r.arcB_.size(); ++j) r.matchedA_(j) = onA.Backward(BToA(onB.Forward(r.arcB_(j))));
  return r;
}

double CentrelineAlignment::AToB(double arcA) const { return analysis::InterpolateLinear(arcA_, matchedB_, arcA); }
double CentrelineAlignment::BToA(double arcB) const { return analysis::InterpolateLinear(arcB_, matchedA_, arcB); }

}  // namespace colonmap::landmarks
