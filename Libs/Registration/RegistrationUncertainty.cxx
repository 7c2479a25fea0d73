#include "Registration/RegistrationUncertainty.h"

#include "Flattening/BeltramiCoefficient.h"
#include "Registration/FeatureMatching.h"
#include "Surface/MeanCurvature.h"
#include "Surface/RingAverage.h"

#include <algorithm>
#include <cmath>
#include <utility>

namespace colonmap::registration {

namespace {

// The models' coefficients, in the order of UncertaintyFeatures: kC the median (least squares of
// log(max(true error, 0.2 mm))), kB the 90% bound (linear quantile regression of the same, tau 0.92:
// fitted at tau 0.9 the bound covered 88.4% of the wall points of pairs it was not fitted on, at
// 0.92 90.2%); every coefficient but the intercept >= 0, polyps weighted 25 to 1 against wall
// points (they are about 2% of the points). Written by scripts/fit_uncertainty.py --bound quantile
// --polyp-weight 25 --tau 0.92 on 42 pairs (refitted 2026-12-06 with the segment deformation
// input, the VHM pairs remade by the deterministic weld; harmonic method, surfaces from our own
// CT pipeline): the tube phantom at deformation 0.5 (seeds 1-10) and 1.0 (seeds 1-8), clinical
// spacing; real-colon pairs of GCA 00020, HuBMAP VHM and VHF (seeds 1-8 each, 1 mm); 8400 wall
// points and 173 polyps. Inputs at 0 came out so
// (RegistrationReliability.h carries those signals). docs/accuracy.md gives the held-back figures.
constexpr double kC[kUncertaintyFeatures] = {-1.6917, 0.2445, 0.5649, 0.2228, 0.0000, 0.4350, 0.0000, 0.0159, 0.4097, 0.2840, 0.0000, 0.0000, 0.4570, 0.5432, 0.4743, 0.7689};
constexpr double kB[kUncertaintyFeatures] = {-0.9065, 0.3802, 0.6069, 0.0548, 0.0000, 0.5407, 0.0000, 0.1289, 0.5092, 0.0000, 0.0000, 0.0000, 0.6056, 0.4468, 0.4153, 1.1755};

}  // namespace

Eigen::Matrix<double, kUncertaintyFeatures, 1> UncertaintyFeatures(const PointEvidence& p, const SegmentEvidence& s) {
  const double K = std::isfinite(p.dilatation) ? std::max(1.0, p.dilatation) : 10.0;
  Eigen::Matrix<double, kUncertaintyFeatures, 1> x;
  x << 1.0, std::log1p(std::max(0.0, p.loo)), std::log1p(std::max(0.0, p.nearMm) / 10.0),
      std::log1p(std::max(0.0, p.correctionMm)), std::log(K), 1.0 - s.pathCorrelation, s.droppedFraction,
      1.0 / (1.0 + s.matchesPer100mm), std::exp(-std::max(0.0, p.flexureMm) / 30.0), 1.0 - s.curvatureAgreement,
      s.lengthMismatch, std::clamp(p.curvature, 0.0, 5.0), p.trusted ? 0.0 : 1.0,
      std::clamp(std::log(std::max(1e-6, p.scale)), -2.0, 3.0), std::log1p(std::max(0.0, p.alongMm) / 10.0),
      std::log1p(std::max(0.0, s.deformationMm) / 10.0);
  return x;
}

namespace {

using Features = Eigen::Matrix<double, kUncertaintyFeatures, 1>;

double MedianOf(const Features& x) { return std::exp(Eigen::Map<const Features>(kC).dot(x)); }

// Two separately fitted linear models can cross far from the data: never below the median.
double Bound90Of(const Features& x) { return std::max(std::exp(Eigen::Map<const Features>(kB).dot(x)), MedianOf(x)); }

PointEvidence EvidenceAt(const UncertaintyComponents& c, Eigen::Index i, bool trusted) {
  return {c.loo(i), c.nearMm(i), c.correctionMm(i), c.dilatation(i), c.flexureMm(i), c.curvature(i), trusted, c.scale(i), c.alongMm(i)};
}

// Median and bound at vertex i, the inputs computed once.
void EvaluateAt(VertexUncertainty& u, Eigen::Index i, const SegmentEvidence& s, bool trusted) {
  const Features x = UncertaintyFeatures(EvidenceAt(u.components, i, trusted), s);
  u.median(i) = MedianOf(x);
  u.bound90(i) = Bound90Of(x);
}

}  // namespace

double UncertaintyMedian(const PointEvidence& p, const SegmentEvidence& s) { return MedianOf(UncertaintyFeatures(p, s)); }

double UncertaintyBound90(const PointEvidence& p, const SegmentEvidence& s) { return Bound90Of(UncertaintyFeatures(p, s)); }

void ApplyTrust(VertexUncertainty& u, const Eigen::VectorXd& trusted) {
  for (Eigen::Index i = 0; i < trusted.size() && i < u.median.size(); ++i)
    if (trusted(i) < 0.5) EvaluateAt(u, i, u.segment, false);
}

namespace {

// Per vertex: exp(mean over its faces of log(sqrt(3D area / flat area) / segmentScale)); 1 for a
// vertex without a face of both areas.
Eigen::VectorXd LocalScale(const FlatSegment& flat, double segmentScale) {
  const Eigen::Index n = flat.uv.rows();
  const Eigen::VectorXd flatArea = flattening::SignedFlatAreas(flat.uv, flat.F).cwiseAbs();
  const Eigen::VectorXd area3 = flattening::SurfaceFaceAreas(flat.position, flat.F);
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(n), count = Eigen::VectorXd::Zero(n);
  for (Eigen::Index f = 0; f < flat.F.rows(); ++f) {
    if (!(area3(f) > 0) || !(flatArea(f) > 0)) continue;
    const double logScale = 0.5 * std::log(area3(f) / flatArea(f)) - std::log(segmentScale);
    for (int j = 0; j < 3; ++j) {
      sum(flat.F(f, j)) += logScale;
      count(flat.F(f, j)) += 1;
    }
  }
  return (sum.array() / count.array().max(1.0)).exp();
}

}  // namespace

double MmPerFlatUnit(const FlatSegment& flat) {
  const double area3 = surface::MixedVertexAreas(flat.position, flat.F).sum();
  const double areaFlat = flattening::SignedFlatAreas(flat.uv, flat.F).cwiseAbs().sum();
  return areaFlat > 0 ? std::sqrt(area3 / areaFlat) : 1.0;
}

double FlatLengthMm(const FlatSegment& flat) {
  return flat.uv.rows() ? (flat.uv.col(1).maxCoeff() - flat.uv.col(1).minCoeff()) * MmPerFlatUnit(flat) : 0.0;
}

VertexUncertainty EstimateUncertainty(const FlatSegment& flat, const Eigen::MatrixXd& h, const Eigen::VectorXd& K,
                                      const std::vector<ConstraintPoint>& constraints, const SegmentEvidence& segment,
                                      const Eigen::VectorXd& meanCurvature, const Eigen::VectorXd& alongMm,
                                      int neighbours) {
  const Eigen::Index n = flat.uv.rows();
  VertexUncertainty out;
  UncertaintyComponents& c = out.components;
  const double scale = MmPerFlatUnit(flat);
  const auto distance = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return PeriodicDifference(a, b, flat.period).norm();
  };
  const std::size_t nc = constraints.size();
  out.mmPerFlatUnit = scale;
  SegmentEvidence evidence = segment;
  {
    std::vector<int> groups;
    for (const ConstraintPoint& p : constraints) groups.push_back(p.group);
    std::sort(groups.begin(), groups.end());
    const double length = (flat.uv.col(1).maxCoeff() - flat.uv.col(1).minCoeff()) * scale;
    evidence.matchesPer100mm =
        length > 0 ? 100.0 * static_cast<double>(std::unique(groups.begin(), groups.end()) - groups.begin()) / length : 0.0;
  }
  out.segment = evidence;
  const std::size_t k = std::min<std::size_t>(std::max(1, neighbours), nc);

  // Leave-one-group-out residual of every constraint (mm).
  std::vector<double> residual(nc, 0.0);
  for (std::size_t a = 0; a < nc; ++a) {
    std::vector<std::pair<double, std::size_t>> near;
    for (std::size_t b = 0; b < nc; ++b)
      if (constraints[b].group != constraints[a].group) near.emplace_back(distance(constraints[a].uv, constraints[b].uv), b);
    if (near.empty()) {
      residual[a] = constraints[a].displacement.norm() * scale;  // nothing predicts it: the correction itself
      continue;
    }
    const std::size_t m = std::min(k, near.size());
    std::partial_sort(near.begin(), near.begin() + m, near.end());
    Eigen::Vector2d predicted(0, 0);
    double wsum = 0;
    for (std::size_t t = 0; t < m; ++t) {
      const double w = 1.0 / (near[t].first * near[t].first + 1e-6);
      predicted += w * constraints[near[t].second].displacement;
      wsum += w;
    }
    residual[a] = (predicted / wsum - constraints[a].displacement).norm() * scale;
  }

  // Per-vertex dilatation: mean over the faces around (+inf capped at 10).
  Eigen::VectorXd ksum = Eigen::VectorXd::Zero(n), kcount = Eigen::VectorXd::Zero(n);
  for (Eigen::Index f = 0; f < flat.F.rows(); ++f)
    for (int j = 0; j < 3; ++j) {
      const double v = f < K.size() && std::isfinite(K(f)) ? std::min(10.0, K(f)) : 10.0;
      ksum(flat.F(f, j)) += v;
      kcount(flat.F(f, j)) += 1;
    }
  c.dilatation = (ksum.array() / kcount.array().max(1.0)).max(1.0);
  c.scale = LocalScale(flat, scale);
  c.alongMm = alongMm.size() == n ? alongMm : Eigen::VectorXd(Eigen::VectorXd::Zero(n));
  // Distances to the segment's ends along v (mm): v is the along-colon coordinate.
  const double vmin = flat.uv.col(1).minCoeff(), vmax = flat.uv.col(1).maxCoeff();
  c.endMm[0] = (flat.uv.col(1).array() - vmin) * scale;
  c.endMm[1] = (vmax - flat.uv.col(1).array()) * scale;
  c.flexureMm = Eigen::VectorXd::Constant(n, kNoFlexureMm);
  for (int e = 0; e < 2; ++e)
    if (segment.flexureAtEnd[e]) c.flexureMm = c.flexureMm.cwiseMin(c.endMm[e]);
  c.curvature = Eigen::VectorXd::Zero(n);
  if (meanCurvature.size() == n) {
    // |H| averaged twice over each vertex and its neighbours (about its 20 nearest vertices).
    const Eigen::VectorXd a = surface::RingAverage(flat.F, meanCurvature.cwiseAbs(), 2);
    c.curvature = (10.0 * a).cwiseMin(5.0);
  }
  c.loo.resize(n);
  c.nearMm.resize(n);
  c.correctionMm = h.rows() == n ? Eigen::VectorXd(h.rowwise().norm() * scale) : Eigen::VectorXd::Zero(n);
  std::vector<std::pair<double, std::size_t>> near(nc);
  for (Eigen::Index i = 0; i < n; ++i) {
    if (nc == 0) {
      // No match: the map is the initial one; nothing local to go by.
      c.loo(i) = 0.0;
      c.nearMm(i) = scale * 1.0;  // one width
      continue;
    }
    const Eigen::Vector2d x = flat.uv.row(i).transpose();
    for (std::size_t a = 0; a < nc; ++a) near[a] = {distance(x, constraints[a].uv), a};
    std::partial_sort(near.begin(), near.begin() + k, near.end());
    c.nearMm(i) = near[0].first * scale;
    const double sigma = std::max(near[k - 1].first, 1e-3);
    double w = 0, e2 = 0;
    for (std::size_t t = 0; t < k; ++t) {
      const double g = std::exp(-0.5 * near[t].first * near[t].first / (sigma * sigma));
      w += g;
      e2 += g * residual[near[t].second] * residual[near[t].second];
    }
    c.loo(i) = std::sqrt(e2 / w);
  }
  out.median.resize(n);
  out.bound90.resize(n);
  for (Eigen::Index i = 0; i < n; ++i) EvaluateAt(out, i, evidence, true);
  return out;
}

}  // namespace colonmap::registration
