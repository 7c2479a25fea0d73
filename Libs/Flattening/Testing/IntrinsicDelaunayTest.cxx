// Intrinsic Delaunay triangulation (Flattening/IntrinsicDelaunay.h) with known answers: on a
// plane it is the Delaunay triangulation of the points (every new edge as long as the straight
// segment, weights >= 0, linear functions still harmonic), the surface area is unchanged, the
// Dirichlet energy of any function does not grow (Rippa's theorem), fixed edges stay; and on a
// tube of obtuse triangles, where the mesh's own cotangent weights fold the flat map, the
// intrinsic Laplacian gives a map without flipped triangles.
#include "Core/TriangleMesh.h"
#include "Flattening/BeltramiCoefficient.h"
#include "Flattening/ConformalFlattening.h"
#include "Flattening/IntrinsicDelaunay.h"
#include "Flattening/PrepareSegment.h"
#include "Surface/MeshTopology.h"
#include "Surface/MeanCurvature.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

namespace {

using namespace colonmap;
using namespace colonmap::flattening;
constexpr double kPi = 3.14159265358979323846;

// A planar grid (nx x ny points, jittered by a fixed pseudo-random pattern) whose quads are all
// split along the same diagonal, on a grid sheared so that that diagonal is the long one: many
// obtuse triangles with negative cotangent weights.
void ShearedGrid(int nx, int ny, Eigen::MatrixXd& V, Eigen::MatrixXi& F) {
  V.resize(nx * ny, 3);
  std::uint32_t s = 12345;
  auto rnd = [&s]() {
    s = s * 1664525u + 1013904223u;
    return (s >> 8) / 16777216.0 - 0.5;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) V.row(j * nx + i) << i + 0.8 * j + 0.2 * rnd(), 0.4 * j + 0.05 * rnd(), 0.0;
  F.resize(2 * (nx - 1) * (ny - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i, b = a + 1, c = a + nx + 1, d = a + nx;
      F.row(f++) << a, b, c;  // diagonal a-c: the long one on this shear
      F.row(f++) << a, c, d;
    }
}

double Area(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  double a = 0;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
  {
    const Eigen::Vector3d e1 = V.row(F(f, 1)) - V.row(F(f, 0)), e2 = V.row(F(f, 2)) - V.row(F(f, 0));
    a += 0.5 * e1.cross(e2).norm();
  }
  return a;
}

double IntrinsicArea(const Eigen::MatrixXd& l) {
  double a = 0;
  for (Eigen::Index f = 0; f < l.rows(); ++f) {
    const double x = l(f, 0), y = l(f, 1), z = l(f, 2), p = 0.5 * (x + y + z);
    a += std::sqrt(std::max(0.0, p * (p - x) * (p - y) * (p - z)));
  }
  return a;
}

// Negative weights on interior edges (those with two faces).
long NegativeInteriorWeights(const Eigen::SparseMatrix<double>& L, const Eigen::MatrixXi& F) {
  std::map<std::pair<int, int>, int> faces;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) ++faces[{std::min(F(f, k), F(f, (k + 1) % 3)), std::max(F(f, k), F(f, (k + 1) % 3))}];
  long n = 0;
  for (const auto& [e, count] : faces)
    if (count == 2 && L.coeff(e.first, e.second) < -1e-10) ++n;
  return n;
}

TEST(IntrinsicDelaunay, OnAPlaneGivesTheDelaunayTriangulationAndKeepsLinearPrecision) {
  Eigen::MatrixXd V;
  Eigen::MatrixXi F;
  ShearedGrid(12, 10, V, F);
  const Eigen::SparseMatrix<double> Lmesh = surface::CotangentLaplacian(V, F);
  ASSERT_GT(NegativeInteriorWeights(Lmesh, F), 0) << "the test mesh should have negative weights";
  const IntrinsicTriangulation T = IntrinsicDelaunay(V, F, {}, false);  // chords allowed: the true Delaunay triangulation
  EXPECT_GT(T.flips, 0);
  EXPECT_GT(T.negativeBefore, 0);
  EXPECT_EQ(T.negativeAfter, 0);
  ASSERT_EQ(T.F.rows(), F.rows());
  // Flat: every intrinsic edge is the straight segment between its ends.
  double worst = 0;
  for (Eigen::Index f = 0; f < T.F.rows(); ++f)
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, std::fabs(T.lengths(f, k) - (V.row(T.F(f, k)) - V.row(T.F(f, (k + 1) % 3))).norm()));
  EXPECT_LT(worst, 1e-9);
  // Orientation kept: every face counter-clockwise in the plane, as the input's.
  for (Eigen::Index f = 0; f < T.F.rows(); ++f) {
    const Eigen::Vector3d e1 = V.row(T.F(f, 1)) - V.row(T.F(f, 0)), e2 = V.row(T.F(f, 2)) - V.row(T.F(f, 0));
    EXPECT_GT(e1.cross(e2).z(), 0.0) << "face " << f;
  }
  // Empty circumcircles: the Delaunay property itself, checked on the points.
  const Eigen::SparseMatrix<double> L = IntrinsicCotangentLaplacian(T.F, T.lengths, V.rows());
  EXPECT_EQ(NegativeInteriorWeights(L, T.F), 0);
  long violations = 0;
  for (Eigen::Index f = 0; f < T.F.rows(); ++f) {
    const Eigen::Vector2d a = V.row(T.F(f, 0)).head(2), b = V.row(T.F(f, 1)).head(2), c = V.row(T.F(f, 2)).head(2);
    const double d = 2 * (a.x() * (b.y() - c.y()) + b.x() * (c.y() - a.y()) + c.x() * (a.y() - b.y()));
    const Eigen::Vector2d o((a.squaredNorm() * (b.y() - c.y()) + b.squaredNorm() * (c.y() - a.y()) + c.squaredNorm() * (a.y() - b.y())) / d,
                            (a.squaredNorm() * (c.x() - b.x()) + b.squaredNorm() * (a.x() - c.x()) + c.squaredNorm() * (b.x() - a.x())) / d);
    const double r = (a - o).norm();
    for (Eigen::Index v = 0; v < V.rows(); ++v)
      if ((Eigen::Vector2d(V.row(v).head(2)) - o).norm() < r * (1 - 1e-9)) ++violations;
  }
  EXPECT_EQ(violations, 0);
  // Linear precision: x and y are harmonic at interior vertices for any planar triangulation.
  const Eigen::MatrixXd LV = L * V;
  std::set<int> boundary;
  for (int v = 0; v < 12; ++v) boundary.insert(v), boundary.insert(9 * 12 + v);
  for (int j = 0; j < 10; ++j) boundary.insert(j * 12), boundary.insert(j * 12 + 11);
  for (Eigen::Index v = 0; v < V.rows(); ++v)
    if (!boundary.count(static_cast<int>(v))) EXPECT_LT(LV.row(v).head(2).norm(), 1e-9) << "vertex " << v;
}

TEST(IntrinsicDelaunay, KeepsAreaLowersDirichletEnergyAndKeepsFixedEdges) {
  // A curved surface: the sheared grid wrapped around a cylinder of radius 3 (not closed).
  Eigen::MatrixXd P;
  Eigen::MatrixXi F;
  ShearedGrid(14, 12, P, F);
  Eigen::MatrixXd V(P.rows(), 3);
  for (Eigen::Index v = 0; v < P.rows(); ++v) V.row(v) << 3 * std::cos(P(v, 1) / 3), 3 * std::sin(P(v, 1) / 3), P(v, 0);
  // Fix the grid's row 5 edges (a path across the mesh).
  std::vector<std::array<int, 2>> keep;
  for (int i = 0; i + 1 < 14; ++i) keep.push_back({5 * 14 + i, 5 * 14 + i + 1});
  const IntrinsicTriangulation T = IntrinsicDelaunay(V, F, keep);
  EXPECT_GT(T.flips, 0);
  EXPECT_NEAR(IntrinsicArea(T.lengths), Area(V, F), 1e-9 * Area(V, F));
  std::set<std::pair<int, int>> edges;
  for (Eigen::Index f = 0; f < T.F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = T.F(f, k), b = T.F(f, (k + 1) % 3);
      edges.insert({std::min(a, b), std::max(a, b)});
    }
  for (const auto& e : keep) EXPECT_TRUE(edges.count({std::min(e[0], e[1]), std::max(e[0], e[1])}));
  // Rippa: Dirichlet energy x' (-L) x of the same vertex values does not grow.
  const Eigen::SparseMatrix<double> Lm = surface::CotangentLaplacian(V, F);
  const Eigen::SparseMatrix<double> Li = IntrinsicCotangentLaplacian(T.F, T.lengths, V.rows());
  for (int c = 0; c < 3; ++c) {
    Eigen::VectorXd x(V.rows());
    for (Eigen::Index v = 0; v < V.rows(); ++v) x(v) = std::sin(0.7 * V(v, 2) + c) * V(v, (c + 1) % 3);
    EXPECT_LE(-x.dot(Li * x), -x.dot(Lm * x) * (1 + 1e-12));
  }
  // Symmetric with zero row sums.
  EXPECT_LT((Eigen::SparseMatrix<double>(Li.transpose()) - Li).norm(), 1e-12 * Li.norm());
  EXPECT_LT((Li * Eigen::VectorXd::Ones(V.rows())).cwiseAbs().maxCoeff(), 1e-9);
}

// A tube (n around, m rings, radius 10 with a bulge) whose end loops zig-zag along mesh edges,
// as the landmarks stage leaves them (its cut loops are closed along edges): at both ends every
// other face with two corners on the end ring is removed, so the loop runs ring, ring + 1,
// ring, ... and the faces along it are obtuse. The rings are turned against each other so the
// diagonals are long.
TriangleMesh ZigZagTube(int n, int m, double ringGap, double turn) {
  TriangleMesh t;
  t.V.resize(static_cast<Eigen::Index>(n) * m, 3);
  Eigen::VectorXd arc(t.V.rows());
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      const double a = 2 * kPi * (j + (i % 2) * turn) / n;
      const double r = 10.0 * (1.0 + 0.3 * std::sin(2 * kPi * i / m));
      t.V.row(i * n + j) << r * std::cos(a), r * std::sin(a), ringGap * i;
      arc(i * n + j) = ringGap * i;
    }
  std::vector<Eigen::Vector3i> faces;
  for (int i = 0; i + 1 < m; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j, b = (i + 1) * n + j, c = (i + 1) * n + (j + 1) % n, d = i * n + (j + 1) % n;
      if (!(i == m - 2 && j % 2 == 0)) faces.emplace_back(a, b, c);  // two corners on ring m-1
      if (!(i == 0 && j % 2 == 0)) faces.emplace_back(a, c, d);      // two corners on ring 0
    }
  t.F.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f) t.F.row(static_cast<Eigen::Index>(f)) = faces[f].transpose();
  t.pointData["CenterlineArcLength"] = DataArray{arc, false};
  return t;
}

TEST(IntrinsicDelaunay, ZigZagEndLoopsFoldWithNeumannEndsButNotWithConjugateFluxEnds) {
  const int n = 40, m = 60;
  const TriangleMesh tube = ZigZagTube(n, m, 0.8, 0.45);
  Eigen::VectorXi path(m - 1);
  for (int i = 1; i < m; ++i) path(i - 1) = i * n + 1;  // column 1 from the zig-zag loop at ring 0 / 1
  ASSERT_EQ(surface::AnalyzeTopology(tube.F).boundaryLoops, 2);
  const Eigen::VectorXd arc = tube.pointData.at("CenterlineArcLength").values.col(0);
  NullProgress np;
  FlatteningOptions before, after;
  before.laplacian = LaplacianMode::Mesh;
  before.ends = EndCondition::Neumann;
  TriangleMesh prepared = tube;
  Eigen::VectorXi preparedPath = path;
  PrepareSegment(prepared, preparedPath);
  const Eigen::VectorXd parc = prepared.pointData.at("CenterlineArcLength").values.col(0);
  const FlatteningResult a = ConformalFlattening(tube.V, tube.F, path, arc, before, np);
  const FlatteningResult b = ConformalFlattening(prepared.V, prepared.F, preparedPath, parc, after, np);
  const DistortionStats qa = SummarizeDistortion(a.cut.V, a.uv, a.cut.F, BeltramiCoefficient(a.cut.V, a.uv, a.cut.F));
  const DistortionStats qb = SummarizeDistortion(b.cut.V, b.uv, b.cut.F, BeltramiCoefficient(b.cut.V, b.uv, b.cut.F));
  std::printf("zig-zag tube: mesh weights, Neumann ends: %ld flips, |mu| mean %.4f; intrinsic, conjugate-flux ends: "
              "%ld flips, |mu| mean %.4f (%ld edge flips, %ld -> %ld negative weights)\n",
              qa.flipped, qa.muMean, qb.flipped, qb.muMean, b.edgeFlips, b.negativeWeightsMesh, b.negativeWeightsUsed);
  EXPECT_GT(qa.flipped, 0) << "Neumann ends on zig-zag loops should fold (the cause the conjugate-flux ends remove)";
  EXPECT_EQ(qb.flipped, 0);
  EXPECT_EQ(b.negativeWeightsUsed, 0);
  // f1 obeys the maximum principle: within [0, 1].
  EXPECT_GE(b.f1.minCoeff(), -1e-12);
  EXPECT_LE(b.f1.maxCoeff(), 1 + 1e-12);
  // The same rectangle within discretisation (the aspect belongs to the surface, not to the
  // triangulation or the end condition).
  EXPECT_NEAR(b.lambda / a.lambda, 1.0, 0.05);
}

}  // namespace

namespace {

// Summed weight per edge (vertex pair) of per-corner weights.
std::map<std::pair<int, int>, double> EdgeSums(const Eigen::MatrixXi& F, const Eigen::MatrixXd& w) {
  std::map<std::pair<int, int>, double> sum;
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = F(f, k), b = F(f, (k + 1) % 3);
      sum[{std::min(a, b), std::max(a, b)}] += w(f, k);
    }
  return sum;
}

TEST(IntrinsicDelaunay, RaisesOnlyTheNegativeEdgesToASmallPositiveWeight) {
  // The sheared grid with a kept row of edges: some kept edges stay negative.
  Eigen::MatrixXd P;
  Eigen::MatrixXi F;
  ShearedGrid(14, 12, P, F);
  Eigen::MatrixXd V(P.rows(), 3);
  for (Eigen::Index v = 0; v < P.rows(); ++v) V.row(v) << P(v, 0), P(v, 1), 0.0;
  std::vector<std::array<int, 2>> keep;
  for (int i = 0; i + 1 < 14; ++i) keep.push_back({5 * 14 + i, 5 * 14 + i + 1});
  const IntrinsicTriangulation T = IntrinsicDelaunay(V, F, keep);
  const Eigen::MatrixXd raw = IntrinsicCornerWeights(T.F, T.lengths, false);
  const Eigen::MatrixXd raised = IntrinsicCornerWeights(T.F, T.lengths, true);
  const auto before = EdgeSums(T.F, raw), after = EdgeSums(T.F, raised);
  int negative = 0;
  for (const auto& [edge, w] : before) {
    if (w < -1e-10) {
      ++negative;
      EXPECT_NEAR(after.at(edge), 1e-6, 1e-15);
    } else {
      EXPECT_EQ(after.at(edge), w);
    }
  }
  ASSERT_GT(negative, 0);
  // The Laplacian from the raised weights: symmetric, zero row sums, no negative off-diagonal.
  const Eigen::SparseMatrix<double> L = CotangentLaplacianFromWeights(T.F, raised, V.rows());
  EXPECT_LT((Eigen::SparseMatrix<double>(L.transpose()) - L).norm(), 1e-12 * L.norm());
  EXPECT_LT((L * Eigen::VectorXd::Ones(V.rows())).cwiseAbs().maxCoeff(), 1e-12);
  for (int c = 0; c < L.outerSize(); ++c)
    for (Eigen::SparseMatrix<double>::InnerIterator it(L, c); it; ++it)
      if (it.row() != it.col()) EXPECT_GT(it.value(), -1e-10);
}

}  // namespace
