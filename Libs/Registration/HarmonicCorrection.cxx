#include "Registration/HarmonicCorrection.h"

#include "Flattening/BeltramiCoefficient.h"
#include "Flattening/HarmonicFunction.h"
#include "Registration/FeatureMatching.h"
#include "Registration/FoldFeatures.h"
#include "Surface/MeanCurvature.h"

#include <algorithm>
#include <map>
#include <set>

namespace colonmap::registration {

namespace {

// Harmonic function on the glued mesh with `fixed` (glued ids) at `values`; 0 when none fixed.
Eigen::VectorXd Harmonic(const Eigen::SparseMatrix<double>& L, const std::vector<int>& fixed, const std::vector<double>& values) {
  if (fixed.empty()) return Eigen::VectorXd::Zero(L.rows());
  const flattening::HarmonicSolver solver(L, fixed);
  return solver.Solve(Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(values.size())));
}

}  // namespace

HarmonicCorrectionResult SolveHarmonicCorrection(const FlatSegment& supine, const Eigen::MatrixXd& etaUV,
                                                 const std::vector<FlatConstraint>& constraints,
                                                 const HarmonicCorrectionOptions& options, ProgressSink& progress) {
  const Eigen::Index n = supine.uv.rows();
  HarmonicCorrectionResult r;
  r.h = Eigen::MatrixXd::Zero(n, 2);
  r.imageUV = etaUV;
  if (constraints.empty()) return r;

  // The cylinder: cut copies glued, so h takes one value per wall point.
  int ng = 0;
  const Eigen::VectorXi g = GlueCutCopies(supine.position, ng);
  Eigen::MatrixXd Pg(ng, 3);
  for (Eigen::Index i = 0; i < n; ++i) Pg.row(g(i)) = supine.position.row(i);
  Eigen::MatrixXi Fg(supine.F.rows(), 3);
  for (Eigen::Index f = 0; f < supine.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) Fg(f, k) = g(supine.F(f, k));
  const Eigen::SparseMatrix<double> L = surface::CotangentLaplacian(Pg, Fg);
  // End loops: the glued mesh's boundary (edges in one face only).
  std::map<std::pair<int, int>, int> edgeFaces;
  for (Eigen::Index f = 0; f < Fg.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = Fg(f, k), b = Fg(f, (k + 1) % 3);
      ++edgeFaces[{std::min(a, b), std::max(a, b)}];
    }
  std::vector<char> endLoop(ng, 0);
  for (const auto& [e, count] : edgeFaces)
    if (count == 1) endLoop[e.first] = endLoop[e.second] = 1;
  std::vector<int> ends;
  for (int v = 0; v < ng; ++v)
    if (endLoop[v]) ends.push_back(v);
  progress.Report(0.1);

  const Eigen::VectorXd etaArea = flattening::SignedFlatAreas(etaUV, supine.F);
  const auto badFaces = [&](const Eigen::MatrixXd& uv) {
    const Eigen::VectorXd area = flattening::SignedFlatAreas(uv, supine.F);
    std::vector<Eigen::Index> bad;
    for (Eigen::Index f = 0; f < area.size(); ++f)
      if (area(f) <= options.minAreaRatio * etaArea(f)) bad.push_back(f);
    return bad;
  };
  std::set<int> dropped;
  Eigen::MatrixXd hg(ng, 2);
  for (int round = 0;; ++round) {
    // Active constraints, one per glued vertex (the first given wins: deterministic).
    std::vector<int> fixed1, fixed2 = ends;
    std::vector<double> values1, values2(ends.size(), 0.0);
    std::vector<const FlatConstraint*> active;
    std::vector<char> seen(ng, 0);
    for (const FlatConstraint& c : constraints) {
      const int v = g(c.vertex);
      if (dropped.count(c.group) || seen[v]) continue;
      seen[v] = 1;
      active.push_back(&c);
      fixed1.push_back(v);
      values1.push_back(c.displacement.x());
      if (!endLoop[v]) {
        fixed2.push_back(v);
        values2.push_back(c.displacement.y());
      }
    }
    hg.col(0) = Harmonic(L, fixed1, values1);
    hg.col(1) = Harmonic(L, fixed2, values2);
    for (Eigen::Index i = 0; i < n; ++i) r.h.row(i) = hg.row(g(i));
    r.imageUV = etaUV + r.h;
    r.constraintsUsed = static_cast<int>(active.size());
    r.rounds = round + 1;
    progress.Report(std::min(0.9, 0.1 + 0.8 * (round + 1) / (options.maxDropRounds + 1.0)));
    const std::vector<Eigen::Index> flipped = badFaces(r.imageUV);
    if (round == 0) r.initialFlips = static_cast<long>(flipped.size());
    if (flipped.empty()) break;
    if (active.empty() || round >= options.maxDropRounds) {
      // Last resort: shrink h; eta alone (scale 0) is one-to-one.
      for (r.scale = 0.5; r.scale > 1e-3; r.scale *= 0.5) {
        r.imageUV = etaUV + r.scale * r.h;
        if (badFaces(r.imageUV).empty()) break;
      }
      if (!(r.scale > 1e-3)) {
        r.scale = 0.0;
        r.imageUV = etaUV;
      }
      r.h *= r.scale;
      break;
    }
    // Drop the constraint group nearest to each reversed face.
    for (Eigen::Index f : flipped) {
      const Eigen::Vector2d c = (supine.uv.row(supine.F(f, 0)) + supine.uv.row(supine.F(f, 1)) + supine.uv.row(supine.F(f, 2))).transpose() / 3.0;
      double best = 1e300;
      int group = -1;
      for (const FlatConstraint* a : active) {
        const double d = PeriodicDifference(supine.uv.row(a->vertex).transpose(), c, supine.period).norm();
        if (d < best) {
          best = d;
          group = a->group;
        }
      }
      dropped.insert(group);
    }
  }
  r.droppedGroups.assign(dropped.begin(), dropped.end());
  progress.Report(1.0);
  return r;
}

}  // namespace colonmap::registration
