#include "Centerline.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "MeshGraph.h"
#include "Surface/MeanCurvature.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::landmarks {

namespace {

int Farthest(const std::vector<double>& d) {
  int best = 0;
  for (std::size_t i = 0; i < d.size(); ++i)
    if (std::isfinite(d[i]) && d[i] > d[static_cast<std::size_t>(best)]) best = static_cast<int>(i);
  return best;
}

// Area-weighted centroids of the vertices binned by value (bins of width step from 0);
// empty bins are skipped. Values that are NaN are ignored.
Eigen::MatrixXd BinCentroids(const Eigen::MatrixXd& V, const Eigen::VectorXd& area, const Eigen::VectorXd& value,
                             double step) {
  double maxValue = 0.0;
  for (Eigen::Index i = 0; i < value.size(); ++i)
    if (std::isfinite(value(i))) maxValue = std::max(maxValue, value(i));
  const int bins = static_cast<int>(maxValue / step) + 1;
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(bins, 3);
  Eigen::VectorXd weight = Eigen::VectorXd::Zero(bins);
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    if (!std::isfinite(value(i))) continue;
    const int b = std::clamp(static_cast<int>(value(i) / step), 0, bins - 1);
    sum.row(b) += area(i) * V.row(i);
    weight(b) += area(i);
  }
  std::vector<Eigen::RowVector3d> pts;
  for (int b = 0; b < bins; ++b)
    if (weight(b) > 0) pts.push_back(sum.row(b) / weight(b));
  Eigen::MatrixXd P(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t i = 0; i < pts.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = pts[i];
  return P;
}

}  // namespace

Eigen::MatrixXd ResamplePolyline(const Eigen::MatrixXd& P, double step) {
  if (P.rows() < 2) return P;
  const Eigen::VectorXd a = analysis::ArcLength(P);
  const double L = a(a.size() - 1);
  const int n = std::max(2, static_cast<int>(std::round(L / step)) + 1);
  Eigen::MatrixXd out(n, 3);
  Eigen::Index j = 0;
  for (int i = 0; i < n; ++i) {
    const double t = L * i / (n - 1);
    while (j + 2 < P.rows() && a(j + 1) < t) ++j;
    const double len = a(j + 1) - a(j);
    const double u = len > 0 ? std::clamp((t - a(j)) / len, 0.0, 1.0) : 0.0;
    out.row(i) = (1 - u) * P.row(j) + u * P.row(j + 1);
  }
  return out;
}

Eigen::MatrixXd SmoothPolyline(const Eigen::MatrixXd& P, double sigma) {
  const Eigen::Index n = P.rows();
  if (n < 3 || sigma <= 0) return P;
  const int r = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> k(static_cast<std::size_t>(2 * r + 1));
  for (int i = -r; i <= r; ++i) k[static_cast<std::size_t>(i + r)] = std::exp(-0.5 * i * i / (sigma * sigma));
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(n, P.cols());
  for (Eigen::Index i = 0; i < n; ++i) {
    // Symmetric window shrunk near the ends, so the ends stay put and are not pulled inwards.
    const int w = static_cast<int>(std::min<Eigen::Index>({static_cast<Eigen::Index>(r), i, n - 1 - i}));
    double ws = 0;
    for (int d = -w; d <= w; ++d) {
      out.row(i) += k[static_cast<std::size_t>(d + r)] * P.row(i + d);
      ws += k[static_cast<std::size_t>(d + r)];
    }
    out.row(i) /= ws;
  }
  return out;
}

Centerline Reversed(const Centerline& c) {
  Centerline r;
  r.points = c.points.colwise().reverse();
  r.arc = analysis::ArcLength(r.points);
  r.endFirst = c.endSecond;
  r.endSecond = c.endFirst;
  r.clearanceBeforeMm = c.clearanceBeforeMm;
  r.clearanceMm = c.clearanceMm;
  r.uncentred = c.uncentred.colwise().reverse();
  return r;
}

Centerline ComputeCenterline(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const CenterlineOptions& o,
                             ProgressSink& progress) {
  const EdgeGraph g = MeshEdgeGraph(V, F);
  progress.Report(0.05);
  // Double sweep: the farthest vertex from any vertex is one extremity of a tube, the farthest
  // from that the other.
  const int start = F(0, 0);
  const int a = Farthest(ShortestPaths(g, {start}));
  progress.Report(0.15);
  const std::vector<double> da = ShortestPaths(g, {a});
  const int b = Farthest(da);
  progress.Report(0.25);
  const Eigen::VectorXd area = surface::MixedVertexAreas(V, F);
  Eigen::VectorXd level(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i) level(i) = std::isfinite(da[i]) ? da[i] : std::nan("");
  Eigen::MatrixXd P = BinCentroids(V, area, level, o.levelBinMm);
  if (P.rows() < 8) throw Error("the surface is too small or not tube-like for a centreline");
  progress.Report(0.35);

  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = true;
  for (int it = 0; it < o.iterations; ++it) {
    P = SmoothPolyline(ResamplePolyline(P, o.stepMm), o.smoothingMm / o.stepMm);
    const analysis::MidlineProjection proj = analysis::ProjectToMidline(V, P, po);
    const Eigen::MatrixXd Q = BinCentroids(V, area, proj.arc, o.stepMm);
    if (Q.rows() >= 8) P = Q;
      progress.Report(0.35 + 0.6 * (it + 1) / std::max(1, o.iterations));
  }
  P = SmoothPolyline(ResamplePolyline(P, o.stepMm), o.smoothingMm / o.stepMm);
  Centerline c;
  Eigen::MatrixXd first;  // the level-set curve (kept when centring)
  if (o.centre) {
    first = P;
    SubProgress sub(progress, 0.4, 0.95);
    const CentringResult centred = CentreInLumen(V, F, P, o.centring, sub);
    P = SmoothPolyline(ResamplePolyline(centred.points, o.stepMm), o.centredSmoothingMm / o.stepMm);
    c.clearanceBeforeMm = centred.meanClearanceBefore;
    c.clearanceMm = centred.meanClearanceAfter;
  }
  // The level sets run from a to b; keep that orientation (the first sample is near a).
  const auto fromA = [&](Eigen::MatrixXd& Q) {
    if (Q.rows() && (Q.row(0) - V.row(a)).norm() > (Q.row(Q.rows() - 1) - V.row(a)).norm()) Q = Q.colwise().reverse().eval();
  };
  fromA(P);
  fromA(first);
  if (first.rows()) c.uncentred = ResamplePolyline(first, o.outputStepMm);
  c.points = ResamplePolyline(P, o.outputStepMm);
  c.arc = analysis::ArcLength(c.points);
  c.endFirst = a;
  c.endSecond = b;
  progress.Report(1.0);
  return c;
}

}  // namespace colonmap::landmarks
