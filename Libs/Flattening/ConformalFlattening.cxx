#include "Flattening/ConformalFlattening.h"

#include "Core/Error.h"
#include "Flattening/HarmonicFunction.h"
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

namespace colonmap::flattening {
namespace {

using Clock = std::chrono::steady_clock;
double Since(Clock::time_point& t) {
  const Clock::time_point now = Clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

}  // namespace

Eigen::MatrixXd FaceGradients(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& x) {
  Eigen::MatrixXd G(F.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    const Eigen::Vector3d n2 = (p1 - p0).cross(p2 - p0);  // |n2| = 2 area
    const double a2 = n2.squaredNorm();
    if (a2 <= 0.0) {
      G.row(f).setZero();
      continue;
    }
    // grad x = sum_k x_k (n x e_k) / (2 A), e_k the edge opposite corner k (counter-clockwise).
    const Eigen::Vector3d g = n2.cross(x(F(f, 0)) * (p2 - p1) + x(F(f, 1)) * (p0 - p2) + x(F(f, 2)) * (p1 - p0)) / a2;
    G.row(f) = g.transpose();
  }
  return G;
}

double MeanIsolineLength(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& x, int levels) {
  if (levels < 1) return 0.0;
  Eigen::VectorXd length = Eigen::VectorXd::Zero(levels);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double xs[3] = {x(F(f, 0)), x(F(f, 1)), x(F(f, 2))};
    const double lo = std::min({xs[0], xs[1], xs[2]}), hi = std::max({xs[0], xs[1], xs[2]});
    const int k0 = std::max(0, static_cast<int>(std::ceil(lo * levels - 0.5)));
    const int k1 = std::min(levels - 1, static_cast<int>(std::floor(hi * levels - 0.5)));
    for (int k = k0; k <= k1; ++k) {
      const double c = (k + 0.5) / levels;
      // The two crossing points on edges whose ends straddle c (half-open test: each isoline
      // crosses a face through exactly two edges unless it passes a vertex).
      Eigen::Vector3d q[2];
      int found = 0;
      for (int e = 0; e < 3 && found < 2; ++e) {
        const double a = xs[e], b = xs[(e + 1) % 3];
        if ((a < c) != (b < c)) {
          const double t = (c - a) / (b - a);
          q[found++] = (1 - t) * V.row(F(f, e)).transpose() + t * V.row(F(f, (e + 1) % 3)).transpose();
        }
      }
      if (found == 2) length(k) += (q[1] - q[0]).norm();
    }
  }
  return length.mean();
}

FlatteningResult ConformalFlattening(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                     const Eigen::VectorXi& path, const Eigen::VectorXd& arcLength,
                                     const FlatteningOptions& options, ProgressSink& progress) {
  FlatteningResult r;
  Clock::time_point t = Clock::now();
  const Eigen::Index n = V.rows();

  // Checks: a manifold, oriented cylinder whose every vertex is used, and a path joining its loops.
  {
    std::vector<char> used(n, 0);
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        if (F(f, c) < 0 || F(f, c) >= n) throw Error("a face has a vertex index out of range");
        used[F(f, c)] = 1;
      }
    const long unused = static_cast<long>(std::count(used.begin(), used.end(), 0));
    if (unused > 0) throw Error(std::to_string(unused) + " vertices are used by no face");
    const surface::TopologyReport topo = surface::AnalyzeTopology(F);
    if (topo.components != 1 || topo.euler != 0 || topo.boundaryLoops != 2 || topo.nonManifoldEdges != 0 ||
        topo.nonManifoldVertices != 0 || topo.inconsistentEdges != 0)
      throw Error("not a topological cylinder (one manifold, oriented component with Euler characteristic 0 and "
                  "two boundary loops): " + topo.Summary());
  }
  std::vector<std::vector<int>> loops = surface::BoundaryLoops(F);
  std::vector<int> loopOf(n, -1);
  for (int l = 0; l < 2; ++l)
    for (int v : loops[l]) loopOf[v] = l;
  if (path.size() < 2) throw Error("the cut path has fewer than two vertices");
  const int first = loopOf[path(0)], last = loopOf[path(path.size() - 1)];
  if (first < 0 || last < 0 || first == last)
    throw Error("the cut path does not run from one boundary loop to the other");
  int g1 = first;
  if (arcLength.size() == n) {
    double mean[2] = {0, 0};
    for (int l = 0; l < 2; ++l) {
      for (int v : loops[l]) mean[l] += arcLength(v);
      mean[l] /= static_cast<double>(loops[l].size());
    }
    g1 = mean[1] > mean[0] ? 1 : 0;
  }
  r.g1 = loops[g1];
  r.g2 = loops[1 - g1];
  r.times.emplace_back("checks", Since(t));
  progress.Report(0.05);

  // f1 on the cylinder.
  const Eigen::SparseMatrix<double> L = surface::CotangentLaplacian(V, F);
  r.times.emplace_back("laplacian", Since(t));
  progress.Report(0.15);
  {
    std::vector<int> fixed(r.g1);
    fixed.insert(fixed.end(), r.g2.begin(), r.g2.end());
    Eigen::VectorXd values = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(fixed.size()));
    values.head(static_cast<Eigen::Index>(r.g1.size())).setOnes();
    r.f1 = HarmonicSolver(L, fixed).Solve(values);
  }
  r.times.emplace_back("f1", Since(t));
  progress.Report(0.45);

  // f2 on the cut disk: f2 = y o original + s, s = 1 on the right copies of the path, 0 elsewhere.
  r.cut = CutAlongPath(V, F, path);
  r.times.emplace_back("cut", Since(t));
  const Eigen::Index k = path.size();
  Eigen::VectorXd jump = Eigen::VectorXd::Zero(r.cut.V.rows());
  jump.tail(k).setOnes();
  if (options.cut == CutCondition::Periodic) {
    // Harmonic across the cut: minimise the cut mesh's Dirichlet energy of y o original + s over
    // y on the cylinder, i.e. L y = -P^T Lc s (P^T sums the rows of a vertex's copies), y fixed
    // to 0 at the path's first vertex (f2 is defined up to a constant; the ends are Neumann).
    const Eigen::SparseMatrix<double> Lc = surface::CotangentLaplacian(r.cut.V, r.cut.F);
    const Eigen::VectorXd Ls = Lc * jump;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < r.cut.V.rows(); ++i) rhs(r.cut.original(i)) -= Ls(i);
    progress.Report(0.55);
    // y = harmonic with a source: solve the reduced system with one Dirichlet vertex (value 0).
    const HarmonicSolver solver(L, {path(0)});
    const Eigen::VectorXd y = solver.SolveWithSource(Eigen::VectorXd::Zero(1), rhs);
    r.f2.resize(r.cut.V.rows());
    for (Eigen::Index i = 0; i < r.cut.V.rows(); ++i) r.f2(i) = y(r.cut.original(i)) + jump(i);
  } else {
    // Dirichlet: f2 = 0 on the left copy, 1 on the right copy of the path.
    const Eigen::SparseMatrix<double> Lc = surface::CotangentLaplacian(r.cut.V, r.cut.F);
    std::vector<int> fixed;
    Eigen::VectorXd values(2 * k);
    for (Eigen::Index i = 0; i < k; ++i) {
      fixed.push_back(path(i));
      values(2 * i) = 0.0;
      fixed.push_back(static_cast<int>(n + i));
      values(2 * i + 1) = 1.0;
    }
    progress.Report(0.55);
    r.f2 = HarmonicSolver(Lc, fixed).Solve(values);
  }
  r.times.emplace_back("f2", Since(t));
  progress.Report(0.85);

  // lambda, then phi = (lambda f2, f1) on the cut disk.
  const Eigen::MatrixXd G1 = FaceGradients(V, F, r.f1);
  const Eigen::MatrixXd G2 = FaceGradients(r.cut.V, r.cut.F, r.f2);
  double num = 0.0, den = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    const Eigen::Vector3d n2 = (p1 - p0).cross(p2 - p0);
    const double area = 0.5 * n2.norm();
    if (area <= 0.0) continue;
    const Eigen::Vector3d nf = n2 / (2.0 * area);
    const Eigen::Vector3d g1f = G1.row(f).transpose(), g2f = G2.row(f).transpose();
    num += area * g1f.dot(nf.cross(g2f));
    den += area * g2f.squaredNorm();
  }
  if (!(den > 0.0) || !std::isfinite(num) || num == 0.0) throw Error("the harmonic functions are degenerate (zero gradients)");
  r.lambda = num / den;
  r.circumferenceMm = MeanIsolineLength(V, F, r.f1, options.circumferenceLevels);
  r.lengthMm = r.circumferenceMm / std::fabs(r.lambda);
  r.scale = options.width == WidthMode::Circumference ? r.circumferenceMm : 1.0;
  // u = sign(lambda) f2, shifted so that the low side of the cut (the left copy when lambda > 0)
  // has mean u = 0 and the high side mean u = 1 (exactly 1 apart); v = f1 / |lambda|.
  const double al = std::fabs(r.lambda), sign = r.lambda > 0 ? 1.0 : -1.0;
  const int lowSide = r.lambda > 0 ? 0 : 1;
  double shift = 0.0;
  for (Eigen::Index i = 0; i < r.cut.V.rows(); ++i)
    if (r.cut.side(i) == lowSide) shift += sign * r.f2(i);
  shift /= static_cast<double>(k);
  r.uv.resize(r.cut.V.rows(), 2);
  for (Eigen::Index i = 0; i < r.cut.V.rows(); ++i) {
    r.uv(i, 0) = r.scale * (sign * r.f2(i) - shift);
    r.uv(i, 1) = r.scale * r.f1(r.cut.original(i)) / al;
  }
  r.times.emplace_back("map", Since(t));
  progress.Report(1.0);
  return r;
}

}  // namespace colonmap::flattening
