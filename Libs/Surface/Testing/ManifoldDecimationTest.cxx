// Manifold-preserving quadric decimation on shapes with known answers.
#include "IO/MeshIO.h"
#include "Surface/ManifoldDecimation.h"
#include "Surface/MeshTopology.h"
#include "Surface/SelfIntersection.h"
#include "SurfaceDistance.h"
#include "TestShapes.h"

#include <algorithm>
#include <vector>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace colonmap::surface {
namespace {

TEST(ManifoldDecimation, SphereStaysAClosedGenusZeroSphere) {
  const TriangleMesh s = testing::Icosphere(20.0, 5);  // 20480 faces
  DecimationOptions o;
  o.targetFaces = 2000;
  NullProgress np;
  const Decimation d = DecimateManifold(s.V, s.F, o, np);
  EXPECT_LE(d.F.rows(), 2000);
  EXPECT_GE(d.F.rows(), 1990);
  const TopologyReport t = AnalyzeTopology(d.F);
  EXPECT_TRUE(t.IsClosedGenusZero()) << t.Summary();
  EXPECT_EQ(FindSelfIntersections(d.V, d.F).pairs, 0);
  double worst = 0.0;
  for (Eigen::Index v = 0; v < d.V.rows(); ++v) worst = std::max(worst, std::fabs(d.V.row(v).norm() - 20.0));
  EXPECT_LT(worst, 0.2);  // vertices stay on the sphere (its chord sag at 2000 faces is ~0.3 mm)
}

TEST(ManifoldDecimation, TorusKeepsItsHandle) {
  const TriangleMesh t = testing::Torus(20.0, 6.0, 200, 60);  // 24000 faces
  DecimationOptions o;
  o.targetFaces = 600;
  NullProgress np;
  const Decimation d = DecimateManifold(t.V, t.F, o, np);
  const TopologyReport r = AnalyzeTopology(d.F);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.euler, 0);
  EXPECT_EQ(r.boundaryLoops, 0);
  EXPECT_EQ(r.nonManifoldEdges, 0);
  EXPECT_EQ(r.nonManifoldVertices, 0);
  EXPECT_EQ(r.inconsistentEdges, 0);
  EXPECT_LE(d.F.rows(), 600);
}

TEST(ManifoldDecimation, ARingTooThinToKeepStaysARing) {
  // A thin torus decimated far: the link condition refuses the collapses that would pinch it.
  const TriangleMesh t = testing::Torus(10.0, 1.0, 120, 24);
  DecimationOptions o;
  o.targetFaces = 10;
  NullProgress np;
  const Decimation d = DecimateManifold(t.V, t.F, o, np);
  EXPECT_EQ(AnalyzeTopology(d.F).euler, 0);
  EXPECT_GT(d.refusedLink, 0);
  EXPECT_GT(d.F.rows(), 10);
}

// Timing on a contour file (COLONMAP_DECIMATE_FILE, e.g. a raw flying-edges contour of a CT).
TEST(ManifoldDecimation, DISABLED_TimeOnFile) {
  const char* file = std::getenv("COLONMAP_DECIMATE_FILE");
  ASSERT_TRUE(file);
  const TriangleMesh m = io::ReadMesh(file, "contour");
  DecimationOptions o;
  if (const char* t = std::getenv("COLONMAP_MAX_TURN")) o.maxNormalTurnDegrees = std::atof(t);
  NullProgress np;
  const Decimation d = DecimateManifold(m.V, m.F, o, np);
  std::printf("%ld -> %ld faces in %.2f s (%ld collapses, refused %ld link, %ld flip): %s\n", (long)m.F.rows(), (long)d.F.rows(),
              d.seconds, d.collapses, d.refusedLink, d.refusedFlip, AnalyzeTopology(d.F).Summary().c_str());
  const auto report = [&](const char* what, const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
    const ClosestPoints to = ClosestOnSurface(m.V, m.F, V), from = ClosestOnSurface(V, F, m.V);
    double minCos = 1.0;
    int needles = 0, caps = 0;
    for (Eigen::Index f = 0; f < F.rows(); ++f) {
      const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
      const double ab = (b - a).norm(), bc = (c - b).norm(), ca = (a - c).norm();
      const double cmax = std::max({-(b - a).dot(a - c) / (ab * ca), -(c - b).dot(b - a) / (bc * ab), -(a - c).dot(c - b) / (ca * bc)});
      if (cmax > std::cos(5.0 * M_PI / 180)) ++needles;
      const double cmin = std::min({-(b - a).dot(a - c) / (ab * ca), -(c - b).dot(b - a) / (bc * ab), -(a - c).dot(c - b) / (ca * bc)});
      if (cmin < std::cos(170.0 * M_PI / 180)) ++caps;
    }
    (void)minCos;
    std::printf("%s: to contour mean %.4f max %.3f; contour to it mean %.4f p99 %.3f max %.3f mm; faces with a corner < 5 deg %d, > 170 deg %d\n", what,
                to.distance.mean(), to.distance.maxCoeff(), from.distance.mean(),
                [&] { std::vector<double> x(from.distance.data(), from.distance.data() + from.distance.size()); std::sort(x.begin(), x.end()); return x[x.size() * 99 / 100]; }(),
                from.distance.maxCoeff(), needles, caps);
  };
  report("ours", d.V, d.F);
  if (const char* other = std::getenv("COLONMAP_DECIMATE_OTHER")) {
    const TriangleMesh q = io::ReadMesh(other, "other");
    report("other", q.V, q.F);
  }
}

}  // namespace
}  // namespace colonmap::surface
