#include "Taeniae.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "MeshGraph.h"
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::landmarks {

namespace {

constexpr int kBins = 72;           // 5 degree angle bins
constexpr int kPhases = kBins / 3;  // phases mod 120 degrees
constexpr double kBinRad = 2.0 * M_PI / kBins;

double Wrap(double a) {  // to (-pi, pi]
  a = std::fmod(a + M_PI, 2.0 * M_PI);
  if (a < 0) a += 2.0 * M_PI;
  return a - M_PI;
}

}  // namespace

std::vector<Taenia> FindTaeniae(const ColonSegments& segs, const Eigen::MatrixXd& centerline, const TaeniaOptions& o,
                                ProgressSink& progress) {
  const TriangleMesh& open = segs.open;
  const Eigen::MatrixXd& V = open.V;
  const Eigen::Index n = V.rows();
  Eigen::VectorXd H;
  if (const auto it = open.pointData.find("MeanCurvature"); it != open.pointData.end() && it->second.values.rows() == n)
    H = it->second.values.col(0);
  else
    H = surface::MeanCurvature(V, open.F);
  const Eigen::VectorXd area = surface::MixedVertexAreas(V, open.F);
  // Frame from the cecum (reversed centreline), first normal anterior.
  const Eigen::MatrixXd Cr = centerline.colwise().reverse();
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  po.normalHint = Eigen::Vector3d(0, -1, 0);
  const analysis::MidlineProjection proj = analysis::ProjectToMidline(V, Cr, po);
  const Eigen::VectorXd arcR = analysis::ArcLength(Cr);
  const double L = arcR(arcR.size() - 1);
  progress.Report(0.2);

  // Fold fraction per (window, angle bin), circularly smoothed.
  const int nW = static_cast<int>(L / o.stepMm) + 1;
  std::vector<std::array<double, kBins>> foldA(static_cast<std::size_t>(nW)), allA(static_cast<std::size_t>(nW));
  const int half = static_cast<int>(std::ceil(0.5 * o.windowMm / o.stepMm));
  for (Eigen::Index v = 0; v < n; ++v) {
    const double a = std::clamp(proj.arc(v), 0.0, L);
    const int b = std::clamp(static_cast<int>(proj.angle(v) / kBinRad), 0, kBins - 1);
    const int w0 = static_cast<int>(std::round(a / o.stepMm));
    for (int w = std::max(0, w0 - half); w <= std::min(nW - 1, w0 + half); ++w) {
      if (std::abs(a - w * o.stepMm) > 0.5 * o.windowMm) continue;
      allA[w][b] += area(v);
      if (H(v) > o.foldCurvature) foldA[w][b] += area(v);
    }
  }
  const int kr = static_cast<int>(std::ceil(3 * o.smoothingDeg / 5.0));
  std::vector<std::array<double, kPhases>> cost(static_cast<std::size_t>(nW)), track(cost.size());
  for (int w = 0; w < nW; ++w) {
    std::array<double, kBins> p{}, q{};
    double fsum = 0, asum = 0;
    for (int b = 0; b < kBins; ++b) fsum += foldA[w][b], asum += allA[w][b];
    const double mean = asum > 0 ? fsum / asum : 0.0;
    for (int b = 0; b < kBins; ++b) p[b] = allA[w][b] > 0 ? foldA[w][b] / allA[w][b] : mean;
    for (int b = 0; b < kBins; ++b) {
      double s = 0, ws = 0;
      for (int d = -kr; d <= kr; ++d) {
        const double g = std::exp(-0.5 * (d * 5.0 / o.smoothingDeg) * (d * 5.0 / o.smoothingDeg));
        s += g * p[(b + d + kBins) % kBins];
        ws += g;
      }
      q[b] = s / ws;
    }
    for (int j = 0; j < kPhases; ++j)
      cost[w][j] = mean > 1e-9 ? (q[j] + q[j + kPhases] + q[j + 2 * kPhases]) / (3.0 * mean) : 1.0;
    // The tracking cost: the same ratio, but with the mean floored, so that a window with
    // hardly any fold (the caecal pole) adds an almost flat cost and the phase coasts through
    // it instead of following a few stray fold patches.
    const double floored = std::max(mean, o.minFoldFraction);
    for (int j = 0; j < kPhases; ++j)
      track[w][j] = mean > 1e-9 ? (q[j] + q[j + kPhases] + q[j + 2 * kPhases]) / (3.0 * floored) : 1.0;
  }
  progress.Report(0.4);

  // Dynamic programming over windows: fold cost plus a penalty on phase change (mod 120).
  std::vector<std::array<double, kPhases>> acc(static_cast<std::size_t>(nW));
  std::vector<std::array<int, kPhases>> from(static_cast<std::size_t>(nW));
  acc[0] = track[0];
  for (int w = 1; w < nW; ++w)
    for (int j = 0; j < kPhases; ++j) {
      double best = std::numeric_limits<double>::infinity();
      int arg = j;
      for (int i = 0; i < kPhases; ++i) {
        int d = std::abs(i - j);
        d = std::min(d, kPhases - d);
        const double c = acc[w - 1][i] + o.phaseChangePenalty * d * d;
        if (c < best) best = c, arg = i;
      }
      acc[w][j] = best + track[w][j];
      from[w][j] = arg;
    }
  std::vector<int> state(static_cast<std::size_t>(nW));
  state[nW - 1] = static_cast<int>(std::min_element(acc[nW - 1].begin(), acc[nW - 1].end()) - acc[nW - 1].begin());
  for (int w = nW - 1; w > 0; --w) state[w - 1] = from[w][state[w]];
  // Unwrapped phase (radians) and contrast per window.
  std::vector<double> phase(static_cast<std::size_t>(nW)), contrast(static_cast<std::size_t>(nW));
  const double third = 2.0 * M_PI / 3.0;
  for (int w = 0; w < nW; ++w) {
    double ph = (state[w] + 0.5) * kBinRad;
    if (w > 0) {
      double d = std::fmod(ph - phase[w - 1], third);
      if (d > 0.5 * third) d -= third;
      if (d < -0.5 * third) d += third;
      ph = phase[w - 1] + d;
    }
    phase[w] = ph;
    contrast[w] = std::clamp(1.0 - cost[w][state[w]], 0.0, 1.0);
  }
  // TL: the band nearest anterior (angle 0) at the cecum.
  int k0 = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(Wrap(phase[0] + k * third)) < std::abs(Wrap(phase[0] + k0 * third))) k0 = k;
  const auto bandAngle = [&](int k, double a) {  // k: 0 TL, 1 TO, 2 TM
    const double t = std::clamp(a / o.stepMm, 0.0, nW - 1.0);
    const int w = std::min(static_cast<int>(t), nW - 2 < 0 ? 0 : nW - 2);
    const double u = nW > 1 ? t - w : 0.0;
    const double ph = nW > 1 ? (1 - u) * phase[w] + u * phase[w + 1] : phase[0];
    return ph + (k0 + k) * third;
  };
  progress.Report(0.5);

  const char* names[3] = {"TL", "TO", "TM"};
  std::vector<Taenia> out;
  for (int s = 0; s < 5; ++s) {
    const TriangleMesh& seg = segs.segment[s];
    const std::vector<int>& ov = segs.openVertex[s];
    const EdgeGraph g = MeshEdgeGraph(seg.V, seg.F);
    const std::vector<std::vector<int>> loops = surface::BoundaryLoops(seg.F);
    if (loops.size() != 2) throw Error(std::string("segment ") + SegmentName(s) + ": not two boundary loops");
    // Start on the anal-side loop (larger arc from the cecum).
    const auto meanArc = [&](const std::vector<int>& loop) {
      double m = 0;
      for (int v : loop) m += proj.arc(ov[v]);
      return m / loop.size();
    };
    const int first = meanArc(loops[0]) > meanArc(loops[1]) ? 0 : 1;
    double conf = 0;
    int cw = 0;
    {
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (int v : ov) lo = std::min(lo, proj.arc(v)), hi = std::max(hi, proj.arc(v));
      for (int w = 0; w < nW; ++w)
        if (w * o.stepMm >= lo && w * o.stepMm <= hi) conf += contrast[w], ++cw;
    }
    conf = cw ? conf / cw : 0.0;
    for (int k = 0; k < 3; ++k) {
      std::vector<double> weight(g.edges.size());
      for (std::size_t e = 0; e < g.edges.size(); ++e) {
        const int a = ov[g.edges[e].first], b = ov[g.edges[e].second];
        const double th = proj.angle(a) + 0.5 * Wrap(proj.angle(b) - proj.angle(a));
        const double d = std::abs(Wrap(th - bandAngle(k, 0.5 * (proj.arc(a) + proj.arc(b)))));
        const double lateral = d * 0.5 * (proj.distance(a) + proj.distance(b)) / o.lateralSigmaMm;
        weight[e] = g.lengths[e] * (1.0 + lateral * lateral);
      }
      std::vector<int> pred;
      const std::vector<double> dist = ShortestPaths(g, loops[first], &weight, &pred);
      int target = loops[1 - first][0];
      for (int v : loops[1 - first])
        if (dist[v] < dist[target]) target = v;
      Taenia t;
      t.name = names[k];
      t.segment = s;
      t.vertices = PathTo(pred, target);
      t.isCut = k == 1;
      t.confidence = conf;
      out.push_back(std::move(t));
    }
    progress.Report(0.5 + 0.1 * (s + 1));
  }
  return out;
}

}  // namespace colonmap::landmarks
