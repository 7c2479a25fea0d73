// Conformal flattening with known answers (issue 6): a straight cylinder maps to a rectangle of
// aspect h / (2 pi r); a bulged tube stays conformal; the harmonic functions keep their boundary
// values and the maximum principle; the cut surface is a disk; zero flips and small |mu| on the
// phantom's true segments (two seeds, supine and prone); bad inputs give clear errors.
#include "Core/Error.h"
#include "Flattening/BeltramiCoefficient.h"
#include "Flattening/ConformalFlattening.h"
#include "Flattening/CutAlongPath.h"
#include "Flattening/HarmonicFunction.h"
#include "Flattening/IntrinsicDelaunay.h"
#include "Flattening/MidpointSubdivision.h"
#include "Flattening/RasterizeFlatImage.h"
#include "Flattening/ShortestCutPath.h"
#include "Flattening/SplitBoundaryChords.h"
#include "PhantomSegments.h"
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <set>
#include <string>

namespace {

using namespace colonmap;
using namespace colonmap::flattening;
constexpr double kPi = 3.14159265358979323846;

// Tube along z with radius r(z), n around, m rings, vertex (i, j) = i * n + j (rings along z),
// faces as in the phantom's true wall. Point data CenterlineArcLength = z.
TriangleMesh Tube(const std::function<double(double)>& radius, double h, int n, int m) {
  TriangleMesh t;
  t.V.resize(static_cast<Eigen::Index>(n) * m, 3);
  Eigen::VectorXd arc(t.V.rows());
  for (int i = 0; i < m; ++i) {
    const double z = h * i / (m - 1);
    for (int j = 0; j < n; ++j) {
      const double a = 2 * kPi * j / n;
      t.V.row(i * n + j) << radius(z) * std::cos(a), radius(z) * std::sin(a), z;
      arc(i * n + j) = z;
    }
  }
  t.F.resize(2 * static_cast<Eigen::Index>(m - 1) * n, 3);
  Eigen::Index f = 0;
  for (int i = 0; i + 1 < m; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j, b = (i + 1) * n + j, c = (i + 1) * n + (j + 1) % n, d = i * n + (j + 1) % n;
      t.F.row(f++) << a, b, c;
      t.F.row(f++) << a, c, d;
    }
  t.pointData["CenterlineArcLength"] = DataArray{arc, false};
  return t;
}

// Column 0 from ring 0 to ring m-1.
Eigen::VectorXi StraightPath(int n, int m) {
  Eigen::VectorXi p(m);
  for (int i = 0; i < m; ++i) p(i) = i * n;
  return p;
}

FlatteningResult Flatten(const TriangleMesh& t, const Eigen::VectorXi& path, WidthMode mode = WidthMode::Unit,
                         CutCondition cut = CutCondition::Periodic) {
  NullProgress np;
  FlatteningOptions o;
  o.width = mode;
  o.cut = cut;
  return ConformalFlattening(t.V, t.F, path, t.pointData.at("CenterlineArcLength").values.col(0), o, np);
}

DistortionStats Stats(const FlatteningResult& r) {
  return SummarizeDistortion(r.cut.V, r.uv, r.cut.F, BeltramiCoefficient(r.cut.V, r.uv, r.cut.F));
}

TEST(Flattening, StraightCylinderMapsToRectangleOfAspectHOver2PiR) {
  const double r = 10.0, h = 80.0;
  const int n = 96, m = 121;
  const TriangleMesh t = Tube([&](double) { return r; }, h, n, m);
  const FlatteningResult f = Flatten(t, StraightPath(n, m));
  // The inscribed 96-gon has perimeter 2 n r sin(pi / n): that is the discrete circumference.
  const double polygon = 2 * n * r * std::sin(kPi / n);
  EXPECT_NEAR(1.0 / std::fabs(f.lambda), h / polygon, 1e-3 * h / polygon);
  EXPECT_NEAR(f.circumferenceMm, polygon, 1e-9 * polygon);
  EXPECT_NEAR(f.lengthMm, h, 1e-3 * h);
  // A rectangle: u in [0, 1], v in [0, aspect], u linear in the angle, v linear in z.
  const double aspect = 1.0 / std::fabs(f.lambda);
  EXPECT_NEAR(f.uv.col(0).minCoeff(), 0.0, 1e-12);
  EXPECT_NEAR(f.uv.col(0).maxCoeff(), 1.0, 1e-12);
  EXPECT_NEAR(f.uv.col(1).maxCoeff(), aspect, 1e-12);
  double errU = 0.0, errV = 0.0;
  for (Eigen::Index i = 0; i < f.uv.rows(); ++i) {
    const int o = f.cut.original(i);
    const double z = t.V(o, 2);
    errV = std::max(errV, std::fabs(f.uv(i, 1) - aspect * z / h));
    if (f.cut.side(i) < 0) {
      // u = angle / 2 pi, or 1 - that, depending on which side of the cut got f2 = 0.
      const double a = (o % n) / static_cast<double>(n);
      errU = std::max(errU, std::min(std::fabs(f.uv(i, 0) - a), std::fabs(f.uv(i, 0) - (1 - a))));
    }
  }
  EXPECT_LT(errU, 1e-6);
  EXPECT_LT(errV, 1e-6 * aspect);
  const DistortionStats s = Stats(f);
  EXPECT_EQ(s.flipped, 0);
  // Each grid cell maps to a similar cell (the polygonal tube unrolls isometrically up to scale).
  EXPECT_LT(s.muMax, 1e-9);
}

TEST(Flattening, WidthModeCircumferenceScalesToMillimetres) {
  const double r = 8.0, h = 50.0;
  const int n = 64, m = 61;
  const TriangleMesh t = Tube([&](double) { return r; }, h, n, m);
  const FlatteningResult unit = Flatten(t, StraightPath(n, m));
  const FlatteningResult mm = Flatten(t, StraightPath(n, m), WidthMode::Circumference);
  EXPECT_NEAR(mm.uv.col(0).maxCoeff(), mm.circumferenceMm, 1e-9);
  EXPECT_NEAR((mm.uv - unit.uv * mm.circumferenceMm).cwiseAbs().maxCoeff(), 0.0, 1e-9);
  // Area of the rectangle ~ surface area of the polygonal tube.
  const double area = mm.circumferenceMm * mm.circumferenceMm / std::fabs(mm.lambda);
  EXPECT_NEAR(area, 2 * n * r * std::sin(kPi / n) * h, 1e-3 * area);
}

TEST(Flattening, BulgedTubeStaysConformal) {
  // Radius 10 mm with a 40 % bulge (Gaussian, sigma 8 mm) mid-way, on a near-square grid.
  const double h = 100.0;
  auto radius = [&](double z) { return 10.0 * (1.0 + 0.4 * std::exp(-std::pow((z - h / 2) / 8.0, 2))); };
  const int n = 128, m = 201;
  const TriangleMesh t = Tube(radius, h, n, m);
  const FlatteningResult f = Flatten(t, StraightPath(n, m));
  const DistortionStats s = Stats(f);
  EXPECT_EQ(s.flipped, 0);
  EXPECT_LT(s.muMean, 0.02);
  EXPECT_LT(s.muMax, 0.1);
  // Conformal, not isometric: the bulge is magnified less than its area grows, so the area ratio
  // spreads while |mu| stays small.
  EXPECT_GT(s.areaRatioMax / s.areaRatioMin, 1.5);
  // Rotational symmetry: u stays proportional to the angle (f2 is exactly theta / 2 pi).
  double errU = 0.0;
  for (Eigen::Index i = 0; i < f.uv.rows(); ++i)
    if (f.cut.side(i) < 0) {
      const double a = (f.cut.original(i) % n) / static_cast<double>(n);
      errU = std::max(errU, std::min(std::fabs(f.uv(i, 0) - a), std::fabs(f.uv(i, 0) - (1 - a))));
    }
  EXPECT_LT(errU, 1e-6);
}

TEST(Flattening, MidpointSubdivisionKeepsTheSurfaceAndHalvesMu) {
  // The bulged tube on a coarse grid (edges ~2.6 mm around, 5 mm along): subdivision must not
  // move the surface, must keep the old vertex ids, the orientation, the cut path and the point
  // data (linear in z: exact at the midpoints), and the map's |mu| must fall about in proportion
  // to the edge length (first order).
  const double h = 100.0;
  auto radius = [&](double z) { return 10.0 * (1.0 + 0.4 * std::exp(-std::pow((z - h / 2) / 8.0, 2))); };
  const int n = 24, m = 21;
  TriangleMesh t = Tube(radius, h, n, m);
  // An integer array takes the value of the edge's end with the smaller index; cell arrays go.
  Eigen::VectorXd ids(t.V.rows());
  for (Eigen::Index i = 0; i < ids.size(); ++i) ids(i) = static_cast<double>(i);
  t.pointData["VertexId"] = DataArray{ids, true};
  t.cellData["FaceId"] = DataArray{Eigen::VectorXd::Zero(t.F.rows()), true};
  auto area = [](const TriangleMesh& x) {
    double total = 0;
    for (Eigen::Index f = 0; f < x.F.rows(); ++f) {
      const Eigen::Vector3d a = x.V.row(x.F(f, 0)), b = x.V.row(x.F(f, 1)), c = x.V.row(x.F(f, 2));
      total += 0.5 * (b - a).cross(c - a).norm();
    }
    return total;
  };
  double previousMu = 0.0;
  for (int levels = 0; levels <= 2; ++levels) {
    TriangleMesh s = t;
    Eigen::VectorXi path = StraightPath(n, m);
    MidpointSubdivision(s, &path, levels);
    const long edges0 = 3L * n * (m - 1) + n;  // the tube's edges: rings, columns, diagonals
    if (levels == 1) {
      EXPECT_EQ(s.F.rows(), 4 * t.F.rows());
      EXPECT_EQ(s.V.rows(), t.V.rows() + edges0);
    }
    EXPECT_TRUE(s.V.topRows(t.V.rows()).isApprox(t.V));
    EXPECT_NEAR(area(s), area(t), 1e-9 * area(t));
    const surface::TopologyReport topo = surface::AnalyzeTopology(s.F);
    EXPECT_EQ(topo.euler, 0);
    EXPECT_EQ(topo.boundaryLoops, 2);
    EXPECT_EQ(topo.inconsistentEdges, 0);
    // Every face's normal points the same way round as the tube's (all inwards here).
    for (Eigen::Index f = 0; f < s.F.rows(); ++f) {
      const Eigen::Vector3d a = s.V.row(s.F(f, 0)), b = s.V.row(s.F(f, 1)), c = s.V.row(s.F(f, 2));
      const Eigen::Vector3d centre = (a + b + c) / 3, normal = (b - a).cross(c - a);
      ASSERT_LT(normal.x() * centre.x() + normal.y() * centre.y(), 0.0) << "face " << f;
    }
    // The path keeps its ends and its length, and joins each vertex to the next by an edge.
    ASSERT_EQ(path.size(), (m - 1) * (1 << levels) + 1);
    EXPECT_EQ(path(0), 0);
    EXPECT_EQ(path(path.size() - 1), (m - 1) * n);
    const std::vector<surface::MeshEdge> meshEdges = surface::MeshEdges(s.F);
    std::set<std::pair<int, int>> edgeSet;
    for (const surface::MeshEdge& e : meshEdges) edgeSet.insert({std::min(e.a, e.b), std::max(e.a, e.b)});
    for (Eigen::Index i = 0; i + 1 < path.size(); ++i)
      EXPECT_TRUE(edgeSet.count({std::min(path(i), path(i + 1)), std::max(path(i), path(i + 1))})) << i;
    const Eigen::VectorXd arc = s.pointData.at("CenterlineArcLength").values.col(0);
    EXPECT_LT((arc - s.V.col(2)).cwiseAbs().maxCoeff(), 1e-12);
    if (levels == 1) {
      EXPECT_TRUE(s.cellData.empty());
      const Eigen::VectorXd id = s.pointData.at("VertexId").values.col(0);
      EXPECT_TRUE(s.pointData.at("VertexId").integer);
      for (const surface::MeshEdge& e : surface::MeshEdges(t.F)) {
        // The midpoint of (a, b): the new vertex at their mean position, joined to both.
        const Eigen::RowVector3d mid = 0.5 * (t.V.row(e.a) + t.V.row(e.b));
        Eigen::Index best = 0;
        (s.V.bottomRows(s.V.rows() - t.V.rows()).rowwise() - mid).rowwise().squaredNorm().minCoeff(&best);
        EXPECT_EQ(id(t.V.rows() + best), std::min(e.a, e.b));
      }
    }
    const DistortionStats q = Stats(Flatten(s, path));
    std::printf("bulged tube, %d subdivision(s): %ld faces, flips %ld, |mu| mean %.5f max %.5f\n", levels, q.faces,
                q.flipped, q.muMean, q.muMax);
    EXPECT_EQ(q.flipped, 0);
    if (levels > 0) {
      EXPECT_LT(q.muMean, 0.65 * previousMu) << levels;
      EXPECT_GT(q.muMean, 0.2 * previousMu) << levels;  // first order, not exact: the facets stay
    }
    previousMu = q.muMean;
  }
  // A path that leaves the mesh's edges is refused.
  TriangleMesh s = t;
  Eigen::VectorXi bad(2);
  bad << 0, 2 * n + 5;
  EXPECT_THROW(MidpointSubdivision(s, &bad, 1), Error);
  // ... and the mesh and the path are left as they were.
  EXPECT_EQ(s.F, t.F);
  EXPECT_EQ(s.V.rows(), t.V.rows());
  EXPECT_EQ(s.pointData.at("CenterlineArcLength").values.rows(), t.V.rows());
  EXPECT_EQ(bad(1), 2 * n + 5);
  // Nothing to do: no faces, or a path of one vertex.
  TriangleMesh empty;
  empty.V = t.V;
  empty.F.resize(0, 3);
  Eigen::VectorXi single(1);
  single << 3;
  MidpointSubdivision(empty, &single, 2);
  EXPECT_EQ(empty.F.rows(), 0);
  EXPECT_EQ(empty.V.rows(), t.V.rows());
  EXPECT_EQ(single.size(), 1);
}

TEST(Flattening, HarmonicFunctionsKeepBoundaryValuesAndMaximumPrinciple) {
  auto radius = [](double z) { return 9.0 + 2.0 * std::sin(z / 7.0); };
  const int n = 48, m = 61;
  const TriangleMesh t = Tube(radius, 60.0, n, m);
  // A twisting path: column shifts by one every 10 rings (via the quad diagonal).
  std::vector<int> p;
  for (int i = 0; i < m; ++i) p.push_back(i * n + (i / 10) % n);
  Eigen::VectorXi path = Eigen::Map<Eigen::VectorXi>(p.data(), static_cast<Eigen::Index>(p.size()));
  const FlatteningResult f = Flatten(t, path);
  const FlatteningResult d = Flatten(t, path, WidthMode::Unit, CutCondition::Dirichlet);
  // g1 = larger arc length = ring m-1 (z = h).
  for (int v : f.g1) EXPECT_EQ(f.f1(v), 1.0);
  for (int v : f.g2) EXPECT_EQ(f.f1(v), 0.0);
  for (int v : f.g1) EXPECT_EQ(v / n, m - 1);
  EXPECT_GE(f.f1.minCoeff(), 0.0);
  EXPECT_LE(f.f1.maxCoeff(), 1.0);
  // Periodic f2: the right copy of each path vertex is exactly 1 above the left copy.
  // Dirichlet f2: 0 and 1 on the two copies, values in between elsewhere (maximum principle).
  const Eigen::Index n0 = t.V.rows();
  for (Eigen::Index i = 0; i < path.size(); ++i) {
    EXPECT_NEAR(f.f2(n0 + i) - f.f2(path(i)), 1.0, 1e-12);
    EXPECT_EQ(d.f2(path(i)), 0.0);
    EXPECT_EQ(d.f2(n0 + i), 1.0);
  }
  EXPECT_GE(d.f2.minCoeff(), -1e-12);
  EXPECT_LE(d.f2.maxCoeff(), 1.0 + 1e-12);
  // Harmonic: zero Laplacian at every free vertex: interior vertices for f1; for f2 every
  // vertex, the cut included (rows of the two copies summed) and the Neumann ends, except the
  // one vertex that fixes the constant; for the Dirichlet f2 all but the cut. The Laplacian is
  // the one the flattening uses: the intrinsic Delaunay one with the cut path kept (f.cut.F are
  // its faces, in the same order as its edge lengths), negative weights raised.
  std::vector<std::array<int, 2>> keep;
  for (Eigen::Index i = 0; i + 1 < path.size(); ++i) keep.push_back({path(i), path(i + 1)});
  const IntrinsicTriangulation T = IntrinsicDelaunay(t.V, t.F, keep);
  const Eigen::MatrixXd weights = IntrinsicCornerWeights(T.F, T.lengths, true);
  const Eigen::SparseMatrix<double> L = CotangentLaplacianFromWeights(T.F, weights, t.V.rows());
  const Eigen::VectorXd r1 = L * f.f1;
  const Eigen::SparseMatrix<double> Lc = CotangentLaplacianFromWeights(f.cut.F, weights, f.cut.V.rows());
  const Eigen::VectorXd r2c = Lc * f.f2, r3 = Lc * d.f2;
  Eigen::VectorXd r2 = Eigen::VectorXd::Zero(n0);
  for (Eigen::Index i = 0; i < f.cut.V.rows(); ++i) r2(f.cut.original(i)) += r2c(i);
  std::vector<char> onLoop(t.V.rows(), 0);
  for (int v : f.g1) onLoop[v] = 1;
  for (int v : f.g2) onLoop[v] = 1;
  double res1 = 0, res2 = 0, res3 = 0;
  for (Eigen::Index i = 0; i < n0; ++i) {
    if (!onLoop[i]) res1 = std::max(res1, std::fabs(r1(i)));
    if (i != path(0)) res2 = std::max(res2, std::fabs(r2(i)));
  }
  for (Eigen::Index i = 0; i < f.cut.V.rows(); ++i)
    if (d.cut.side(i) < 0) res3 = std::max(res3, std::fabs(r3(i)));
  EXPECT_LT(res1, 1e-10);
  EXPECT_LT(res2, 1e-10);
  EXPECT_LT(res3, 1e-10);
  EXPECT_EQ(Stats(f).flipped, 0);
  // The periodic cut is the better map: smaller mean distortion than the Dirichlet one.
  EXPECT_LT(Stats(f).muMean, Stats(d).muMean);
}

TEST(Flattening, CutSurfaceIsADiskWithOneCopyPerPathVertex) {
  const int n = 32, m = 21;
  const TriangleMesh t = Tube([](double) { return 5.0; }, 20.0, n, m);
  const Eigen::VectorXi path = StraightPath(n, m);
  const CutMesh c = CutAlongPath(t.V, t.F, path);
  EXPECT_EQ(c.V.rows(), t.V.rows() + m);
  const surface::TopologyReport r = surface::AnalyzeTopology(c.F);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.euler, 1);
  EXPECT_EQ(r.boundaryLoops, 1);
  EXPECT_EQ(r.inconsistentEdges, 0);
  // The boundary: both loops (n + 1 vertices each after the cut) and both copies of the path.
  EXPECT_EQ(static_cast<long>(surface::BoundaryLoops(c.F)[0].size()), 2L * (n + 1) + 2L * (m - 2));
  for (int i = 0; i < m; ++i) {
    EXPECT_EQ(c.side(path(i)), 0);
    EXPECT_EQ(c.side(t.V.rows() + i), 1);
    EXPECT_EQ(c.original(t.V.rows() + i), path(i));
  }
}

TEST(Flattening, BadPathsAndMeshesGiveClearErrors) {
  const int n = 16, m = 11;
  const TriangleMesh t = Tube([](double) { return 5.0; }, 10.0, n, m);
  NullProgress np;
  const Eigen::VectorXd arc = t.pointData.at("CenterlineArcLength").values.col(0);
  auto message = [&](const Eigen::MatrixXi& F, const Eigen::VectorXi& path) {
    try {
      ConformalFlattening(t.V, F, path, arc, FlatteningOptions{}, np);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  // Path ending inside the surface.
  Eigen::VectorXi shortPath = StraightPath(n, m).head(5);
  EXPECT_NE(message(t.F, shortPath).find("from one boundary loop to the other"), std::string::npos);
  // Path jumping between vertices without an edge (column 0 then column 5).
  Eigen::VectorXi jump = StraightPath(n, m);
  for (int i = 5; i < m; ++i) jump(i) += 5;
  EXPECT_FALSE(message(t.F, jump).empty());
  // Path touching the first loop again after leaving it.
  std::vector<int> t3 = {0, n, n + 1, 1};
  for (int i = 1; i < m; ++i) t3.push_back(i * n + 2);
  const Eigen::VectorXi touch = Eigen::Map<Eigen::VectorXi>(t3.data(), static_cast<Eigen::Index>(t3.size()));
  EXPECT_NE(message(t.F, touch).find("touch the boundary"), std::string::npos) << message(t.F, touch);
  // Not a cylinder: a hole punched in the middle (three boundary loops).
  Eigen::MatrixXi holed(t.F.rows() - 2, 3);
  const Eigen::Index skip = 2 * (5 * n + 8);
  holed << t.F.topRows(skip), t.F.bottomRows(t.F.rows() - skip - 2);
  EXPECT_NE(message(holed, StraightPath(n, m)).find("not a topological cylinder"), std::string::npos);
}

TEST(Flattening, ShortestCutPathJoinsTheLoopsAndFlattens) {
  const int n = 40, m = 41;
  auto radius = [](double z) { return 6.0 + 0.5 * z / 40.0; };
  const TriangleMesh t = Tube(radius, 40.0, n, m);
  const std::vector<std::vector<int>> loops = surface::BoundaryLoops(t.F);
  const Eigen::VectorXi path = ShortestCutPath(t.V, t.F, loops[0], loops[1]);
  ASSERT_GE(path.size(), m);
  // Straight along one column: m vertices, length h.
  EXPECT_EQ(path.size(), m);
  const FlatteningResult f = Flatten(t, path);
  EXPECT_EQ(Stats(f).flipped, 0);
}

TEST(Flattening, RasterizationInterpolatesLinearFunctionsExactly) {
  // A flat 3 x 2 rectangle split into triangles; values = 2u + 3v + 1 everywhere linear.
  const int n = 7, m = 5;
  Eigen::MatrixXd uv(n * m, 2);
  Eigen::VectorXd val(n * m);
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      uv.row(i * n + j) << 3.0 * j / (n - 1), 2.0 * i / (m - 1);
      val(i * n + j) = 2 * uv(i * n + j, 0) + 3 * uv(i * n + j, 1) + 1;
    }
  Eigen::MatrixXi F(2 * (n - 1) * (m - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < m; ++i)
    for (int j = 0; j + 1 < n; ++j) {
      const int a = i * n + j, b = a + 1, c = a + n + 1, d = a + n;
      F.row(f++) << a, b, c;
      F.row(f++) << a, c, d;
    }
  RasterInfo info;
  const Volume<float> img = RasterizeFlatImage(uv, F, val, 3.0, 2.0, 30, 20, &info);
  EXPECT_EQ(info.covered, 600);
  EXPECT_EQ(info.filled, 0);
  double err = 0;
  for (int j = 0; j < 20; ++j)
    for (int i = 0; i < 30; ++i) {
      const Eigen::Vector3d p = img.IndexToPhysical(Eigen::Vector3d(i, j, 0));
      err = std::max(err, std::fabs(img.At(i, j, 0) - (2 * p.x() + 3 * p.y() + 1)));
    }
  EXPECT_LT(err, 1e-5);
}

TEST(Flattening, BeltramiOfKnownAffineMaps) {
  // One triangle in the plane z = 0; the map (x, y) -> (x + k y, y) has mu = -i k / (2 + i k)...
  // check against the formula mu = (a - d + i (c + b)) / (a + d + i (c - b)).
  Eigen::MatrixXd V(3, 3);
  V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  Eigen::MatrixXi F(1, 3);
  F << 0, 1, 2;
  const double a = 2.0, b = 0.5, c = -0.3, d = 1.5;
  Eigen::MatrixXd uv(3, 2);
  for (int k = 0; k < 3; ++k) uv.row(k) << a * V(k, 0) + b * V(k, 1), c * V(k, 0) + d * V(k, 1);
  const std::complex<double> expected = std::complex<double>(a - d, c + b) / std::complex<double>(a + d, c - b);
  EXPECT_NEAR(std::abs(BeltramiCoefficient(V, uv, F)(0) - expected), 0.0, 1e-12);
  // A similarity (rotation + scale) is conformal; a reflection is flipped (|mu| > 1).
  for (int k = 0; k < 3; ++k) uv.row(k) << 2 * V(k, 0) - V(k, 1), V(k, 0) + 2 * V(k, 1);
  EXPECT_NEAR(std::abs(BeltramiCoefficient(V, uv, F)(0)), 0.0, 1e-12);
  EXPECT_GT(SignedFlatAreas(uv, F)(0), 0.0);
  for (int k = 0; k < 3; ++k) uv.row(k) << V(k, 0), -V(k, 1);
  EXPECT_GT(std::abs(BeltramiCoefficient(V, uv, F)(0)), 1.0);
  EXPECT_LT(SignedFlatAreas(uv, F)(0), 0.0);
}

// The phantom's true segments at test density (2 mm along s, 96 around): zero flips, mean
// |mu| <= 0.02, v increasing towards the cecum, in both scans of two seeds.
TEST(Flattening, PhantomTruthSegmentsHaveNoFlipsAndSmallDistortion) {
  using namespace colonmap::phantom;
  for (std::uint32_t seed : {1u, 2u}) {
    PhantomOptions o;
    o.seed = seed;
    o.meshStepMm = 2.0;
    o.meshPointsAround = 96;
    const ColonAnatomy anatomy = MakeAnatomy(o);
    for (Posture posture : {Posture::Supine, Posture::Prone}) {
      const ScanGeometry scan = MakeScan(anatomy, posture, o);
      const auto segments = flattening::testing::PhantomTruthSegments(scan, o);
      ASSERT_EQ(segments.size(), 5u);
      for (const auto& seg : segments) {
        const FlatteningResult f = Flatten(seg.mesh, seg.taenia[1]);
        const DistortionStats s = Stats(f);
        std::printf("seed %u %s %s: %ld faces, flips %ld, |mu| mean %.4f p99 %.4f max %.4f, width %.1f mm, "
                    "length %.1f mm\n", seed, posture == Posture::Supine ? "supine" : "prone",
                    SegmentName(seg.id), s.faces, s.flipped, s.muMean, s.muP99, s.muMax, f.circumferenceMm,
                    f.lengthMm);
        EXPECT_EQ(s.flipped, 0) << "segment " << SegmentName(seg.id);
        EXPECT_LE(s.muMean, 0.02) << "segment " << SegmentName(seg.id);
        // v grows with CenterlineArcLength (towards the cecum): compare the ends' material s.
        const Eigen::MatrixXd& ms = seg.mesh.pointData.at("MaterialS").values;
        EXPECT_LT(ms(f.g1[0], 0), ms(f.g2[0], 0));
        // The length in the flat map is close to the segment's material length along s
        // (conformal: lengths scale with the local circumference, and segments are tubes).
        const double sLength = ms.maxCoeff() - ms.minCoeff();
        EXPECT_GT(f.lengthMm, 0.5 * sLength);
        EXPECT_LT(f.lengthMm, 2.0 * sLength);
      }
    }
  }
}

}  // namespace

// A face with all three corners on an end loop collapses under f1's Dirichlet values unless it
// is split; after the split the flat map has no zero-area or flipped face.
TEST(Flattening, BoundaryEarsAreSplitAndKeepTheirArea) {
  const int n = 12, m = 6;
  TriangleMesh t = Tube([](double) { return 10.0; }, 30.0, n, m);
  // An ear on the top loop: a face over the boundary edge top(1) -> top(0) with its tip outside.
  const int top = (m - 1) * n, tip = static_cast<int>(t.V.rows());
  t.V.conservativeResize(tip + 1, 3);
  t.V.row(tip) << 13.0 * std::cos(kPi / n), 13.0 * std::sin(kPi / n), 32.0;
  auto& arc = t.pointData.at("CenterlineArcLength").values;
  arc.conservativeResize(tip + 1, 1);
  arc(tip) = 32.0;
  t.F.conservativeResize(t.F.rows() + 1, 3);
  t.F.row(t.F.rows() - 1) << top + 1, top, tip;
  ASSERT_EQ(surface::BoundaryLoops(t.F).size(), 2u);
  NullProgress np;
  {  // Unsplit, the ear collapses: its flat area is zero.
    const FlatteningResult r = ConformalFlattening(t.V, t.F, StraightPath(n, m), arc.col(0), FlatteningOptions(), np);
    EXPECT_GE(Stats(r).flipped, 1);
  }
  const Eigen::Index faces = t.F.rows();
  EXPECT_EQ(SplitBoundaryChords(t), 1);  // the ear's base top(0)-top(1) is the only chord
  EXPECT_EQ(t.F.rows(), faces + 2);
  EXPECT_EQ(surface::EulerCharacteristic(t.F), 0);
  EXPECT_EQ(surface::BoundaryLoops(t.F).size(), 2u);
  EXPECT_NEAR(t.pointData.at("CenterlineArcLength").values(tip + 1, 0), 30.0, 1e-12);
  const FlatteningResult r = Flatten(t, StraightPath(n, m));
  EXPECT_EQ(Stats(r).flipped, 0);
}
