#include "Flattening/ConformalFlattening.h"

#include "Core/Error.h"
#include "Flattening/HalfEdges.h"
#include "Flattening/HarmonicFunction.h"
#include "Flattening/IntrinsicDelaunay.h"
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <functional>
#include <iterator>
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

Eigen::VectorXd ConjugateFluxEndValues(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& f1, const CutMesh& cut,
                                       const Eigen::VectorXi& path, const std::vector<int>& g1, const std::vector<int>& g2,
                                       long* nonPositive) {
  const Eigen::Index n = L.rows();
  const Eigen::VectorXd Lf1 = L * f1;  // at a loop vertex: the flux of f1 into it (sign by loop)
  Eigen::VectorXd values(static_cast<Eigen::Index>(g1.size() + g2.size()));
  Eigen::Index offset = 0;
  long bad = 0;
  for (int l = 0; l < 2; ++l) {
    const std::vector<int>& loop = l == 0 ? g1 : g2;
    const int m = static_cast<int>(loop.size());
    // Where the cut meets this loop, and which way round the loop leads from the cut's left copy
    // (u = 0) to its right copy (u = 1): the way whose first boundary edge lies in a face that
    // kept the left copy's index.
    int start = -1;
    for (int i = 0; i < m && start < 0; ++i)
      if (loop[i] == path(0) || loop[i] == path(path.size() - 1)) start = i;
    if (start < 0) throw Error("the cut path does not end on an end loop");
    const int p = loop[start], nextVertex = loop[(start + 1) % m];
    int step = 0;
    for (Eigen::Index f = 0; f < cut.F.rows() && step == 0; ++f) {
      bool hasNext = false;
      int copy = -1;
      for (int c = 0; c < 3; ++c) {
        if (cut.original(cut.F(f, c)) == nextVertex) hasNext = true;
        if (cut.original(cut.F(f, c)) == p) copy = cut.F(f, c);
      }
      if (hasNext && copy >= 0) step = copy == p ? 1 : -1;
    }
    if (step == 0) throw Error("the cut path's end has no boundary face");
    // Flux per loop vertex (positive where f1 rises into the surface at g2, falls at g1), kept
    // positive so that u is strictly monotone along the loop (non-positive values come only from
    // negative cotangent weights left next to the loop).
    std::vector<double> q(m);
    double total = 0.0;
    for (int i = 0; i < m; ++i) {
      const int v = loop[static_cast<std::size_t>(((start + step * i) % m + m) % m)];
      q[i] = l == 0 ? -Lf1(v) : Lf1(v);
      total += std::max(q[i], 0.0);
    }
    const double floor = 1e-3 * total / m;
    total = 0.0;
    for (double& x : q) {
      if (!(x > floor)) {
        ++bad;
        x = floor;
      }
      total += x;
    }
    // u at a vertex: the flux through the loop from the cut's left copy to the vertex's dual cell
    // centre (half its own share), over the total: 0 at the cut, rising to 1 at its right copy.
    double acc = 0.0;
    for (int i = 0; i < m; ++i) {
      const int idx = ((start + step * i) % m + m) % m;
      values(offset + idx) = i == 0 ? 0.0 : (acc + 0.5 * q[i]) / total;
      acc += i == 0 ? 0.5 * q[0] : q[i];
    }
    offset += m;
  }
  if (nonPositive) *nonPositive = bad;
  return values;
}

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
  }
  std::vector<std::vector<int>> loops;
  if (!IsCylinder(F, n, loops)) {
    const surface::TopologyReport topo = surface::AnalyzeTopology(F);  // for the message
    throw Error("not a topological cylinder (one manifold, oriented component with Euler characteristic 0 and "
                "two boundary loops): " + topo.Summary());
  }
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

  // The Laplacian of the cylinder and, sharing its triangulation, that of the cut disk.
  std::function<Eigen::SparseMatrix<double>(const CutMesh&)> cutLaplacian;
  Eigen::SparseMatrix<double> L;
  CutMesh cutUsed;  // the cut of the triangulation the Laplacians belong to
  if (options.laplacian == LaplacianMode::IntrinsicDelaunay) {
    std::vector<std::array<int, 2>> keep;
    for (Eigen::Index i = 0; i + 1 < path.size(); ++i) keep.push_back({path(i), path(i + 1)});
    const IntrinsicTriangulation T = IntrinsicDelaunay(V, F, keep);
    r.edgeFlips = T.flips;
    r.negativeWeightsMesh = T.negativeBefore;
    r.negativeWeightsUsed = T.negativeAfter;
    const Eigen::MatrixXd weights = IntrinsicCornerWeights(T.F, T.lengths, true);
    L = CotangentLaplacianFromWeights(T.F, weights, n);
    r.negativeWeightsOnCut = T.negativeFixed;
    cutUsed = CutAlongPath(V, T.F, path);  // same vertex numbering as CutAlongPath(V, F, path)
    // How far the drawn faces can be from the surface: an intrinsic edge is a geodesic of length
    // l between two vertices at distance d; the geodesic lies within the ellipse of foci at the
    // ends and major axis l, so every point of the straight edge is within sqrt(l^2 - d^2) / 2
    // of the surface.
    for (Eigen::Index f = 0; f < T.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) {
        const double l = T.lengths(f, c), d = (V.row(T.F(f, c)) - V.row(T.F(f, (c + 1) % 3))).norm();
        r.edgeGapBound = std::max(r.edgeGapBound, 0.5 * std::sqrt(std::max(0.0, l * l - d * d)));
      }
    {
      std::vector<std::array<int, 3>> a(static_cast<std::size_t>(F.rows())), b(a.size());
      for (Eigen::Index f = 0; f < F.rows(); ++f) {
        a[f] = {F(f, 0), F(f, 1), F(f, 2)};
        b[f] = {T.F(f, 0), T.F(f, 1), T.F(f, 2)};
        std::sort(a[f].begin(), a[f].end());
        std::sort(b[f].begin(), b[f].end());
      }
      std::sort(a.begin(), a.end());
      std::sort(b.begin(), b.end());
      std::vector<std::array<int, 3>> common;
      std::set_intersection(a.begin(), a.end(), b.begin(), b.end(), std::back_inserter(common));
      r.changedFaces = F.rows() - static_cast<long>(common.size());
    }
    cutLaplacian = [weights](const CutMesh& c) { return CotangentLaplacianFromWeights(c.F, weights, c.V.rows()); };
  } else {
    L = surface::CotangentLaplacian(V, F);
    cutLaplacian = [](const CutMesh& c) { return surface::CotangentLaplacian(c.V, c.F); };
  }
  r.times.emplace_back("laplacian", Since(t));
  progress.Report(0.15);

  // f1 on the cylinder. The solver (its factorisation) is kept: with conjugate-flux ends f2 has
  // the same constrained vertices.
  std::vector<int> fixed(r.g1);
  fixed.insert(fixed.end(), r.g2.begin(), r.g2.end());
  const HarmonicSolver ends(L, fixed);
  {
    Eigen::VectorXd values = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(fixed.size()));
    values.head(static_cast<Eigen::Index>(r.g1.size())).setOnes();
    r.f1 = ends.Solve(values);
  }
  r.times.emplace_back("f1", Since(t));
  progress.Report(0.45);

  // f2 on the cut disk: f2 = y o original + s, s = 1 on the right copies of the path, 0 elsewhere.
  // The map is drawn on the faces it was computed with (Tutte: fold-free on those).
  if (options.laplacian == LaplacianMode::IntrinsicDelaunay) r.cut = cutUsed;
  else r.cut = cutUsed = CutAlongPath(V, F, path);
  const Eigen::SparseMatrix<double> Lc = cutLaplacian(cutUsed);
  r.times.emplace_back("cut", Since(t));
  const Eigen::Index k = path.size();
  Eigen::VectorXd jump = Eigen::VectorXd::Zero(r.cut.V.rows());
  jump.tail(k).setOnes();
  if (options.cut == CutCondition::Periodic) {
    // Harmonic across the cut: minimise the cut mesh's Dirichlet energy of y o original + s over
    // y on the cylinder, i.e. L y = -P^T Lc s at the free vertices (P^T sums the rows of a
    // vertex's copies).
    const Eigen::VectorXd Ls = Lc * jump;
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n);
    for (Eigen::Index i = 0; i < r.cut.V.rows(); ++i) rhs(r.cut.original(i)) -= Ls(i);
    progress.Report(0.55);
    Eigen::VectorXd y;
    if (options.ends == EndCondition::ConjugateFlux) {
      // y on the end loops from f1's flux, then harmonic inside with the same factorisation.
      const Eigen::VectorXd values = ConjugateFluxEndValues(L, r.f1, r.cut, path, r.g1, r.g2, &r.nonPositiveFlux);
      y = ends.SolveWithSource(values, rhs);
    } else {
      // Neumann ends: one Dirichlet vertex (value 0; f2 is defined up to a constant).
      const HarmonicSolver solver(L, {path(0)});
      y = solver.SolveWithSource(Eigen::VectorXd::Zero(1), rhs);
    }
    r.f2.resize(r.cut.V.rows());
    for (Eigen::Index i = 0; i < r.cut.V.rows(); ++i) r.f2(i) = y(r.cut.original(i)) + jump(i);
    if (options.ends == EndCondition::ConjugateFlux) {
      // The twist between the loops is free: add c f1 with c minimising the Dirichlet energy
      // E(f2 + c f1) (f1 is harmonic with constant ends, so this only turns one loop against the
      // other), which is what the Neumann condition would choose.
      Eigen::VectorXd F1(r.cut.V.rows());
      for (Eigen::Index i = 0; i < F1.size(); ++i) F1(i) = r.f1(r.cut.original(i));
      const Eigen::VectorXd LF1 = Lc * F1;
      const double e11 = F1.dot(LF1);
      if (e11 != 0.0) r.f2 -= (r.f2.dot(LF1) / e11) * F1;
    }
  } else {
    // Dirichlet: f2 = 0 on the left copy, 1 on the right copy of the path.
    std::vector<int> cutFixed;
    Eigen::VectorXd values(2 * k);
    for (Eigen::Index i = 0; i < k; ++i) {
      cutFixed.push_back(path(i));
      values(2 * i) = 0.0;
      cutFixed.push_back(static_cast<int>(n + i));
      values(2 * i + 1) = 1.0;
    }
    progress.Report(0.55);
    r.f2 = HarmonicSolver(Lc, cutFixed).Solve(values);
  }
  r.times.emplace_back("f2", Since(t));
  progress.Report(0.85);

  // lambda (see the header), then phi = (lambda f2, f1) on the cut disk.
  double num = 0.0;
  for (Eigen::Index f = 0; f < r.cut.F.rows(); ++f) {
    const int a = r.cut.F(f, 0), b = r.cut.F(f, 1), c = r.cut.F(f, 2);
    const double x0 = r.f2(a), y0 = r.f1(r.cut.original(a));
    num += 0.5 * ((r.f2(b) - x0) * (r.f1(r.cut.original(c)) - y0) - (r.f2(c) - x0) * (r.f1(r.cut.original(b)) - y0));
  }
  const double den = -0.5 * r.f2.dot(Lc * r.f2);  // Dirichlet energy: x' L x = -sum_edges w_ij (x_i - x_j)^2
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
