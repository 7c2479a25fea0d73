// True wall meshes: topology, orientation, arrays, determinism, dilatation between scans.
#include "PhantomTestUtils.h"

#include <gtest/gtest.h>

#include <map>
#include <set>

using namespace colonmap;
using namespace colonmap::phantom;
using namespace colonmap::phantom::testing;

TEST(PhantomMesh, OpenCylinderWithInwardNormalsAndArrays) {
  PhantomOptions o = CoarseOptions(1, 0.5);
  o.meshStepMm = 2.0;
  o.meshPointsAround = 64;
  const ColonAnatomy a = MakeAnatomy(o);
  const ScanGeometry scan = MakeScan(a, Posture::Prone, o);
  const TriangleMesh m = TrueWall(scan, o);
  // Euler characteristic and boundary loops.
  std::map<std::pair<int, int>, int> edges;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f)
    for (int e = 0; e < 3; ++e) {
      const int u = m.F(f, e), v = m.F(f, (e + 1) % 3);
      ++edges[{std::min(u, v), std::max(u, v)}];
    }
  EXPECT_EQ(m.V.rows() - static_cast<Eigen::Index>(edges.size()) + m.F.rows(), 0);
  std::map<int, std::vector<int>> boundary;
  for (const auto& e : edges) {
    ASSERT_LE(e.second, 2);
    if (e.second == 1) boundary[e.first.first].push_back(e.first.second), boundary[e.first.second].push_back(e.first.first);
  }
  std::set<int> seen;
  int loops = 0;
  for (const auto& b : boundary) {
    if (seen.count(b.first)) continue;
    ++loops;
    std::vector<int> stack{b.first};
    while (!stack.empty()) {
      const int v = stack.back();
      stack.pop_back();
      if (!seen.insert(v).second) continue;
      for (int w : boundary[v]) stack.push_back(w);
    }
  }
  EXPECT_EQ(loops, 2);
  // Normals point into the lumen: towards the centreline point of the face.
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a0 = m.V.row(m.F(f, 0)), b0 = m.V.row(m.F(f, 1)), c0 = m.V.row(m.F(f, 2));
    const Eigen::Vector3d n = (b0 - a0).cross(c0 - a0);
    const double s = m.pointData.at("MaterialS").values(m.F(f, 0), 0);
    ASSERT_GT(n.dot(scan.CenterPoint(s) - a0), 0.0) << f;
  }
  ASSERT_TRUE(m.pointData.count("MaterialS") && m.pointData.count("MaterialTheta") && m.pointData.count("SegmentId"));
  EXPECT_TRUE(m.pointData.at("SegmentId").integer);
  EXPECT_FALSE(m.pointData.at("MaterialS").integer);
  const auto& th = m.pointData.at("MaterialTheta").values;
  EXPECT_GE(th.minCoeff(), 0.0);
  EXPECT_LT(th.maxCoeff(), 2 * kPi);
  const auto& seg = m.pointData.at("SegmentId").values;
  EXPECT_EQ(seg.minCoeff(), 0.0);
  EXPECT_EQ(seg.maxCoeff(), 4.0);
  EXPECT_DOUBLE_EQ(m.pointData.at("MaterialS").values.maxCoeff(), a.length);
}

TEST(PhantomMesh, DeterministicSharedConnectivitySeedMatters) {
  PhantomOptions o = CoarseOptions(3, 0.5);
  const ColonAnatomy a = MakeAnatomy(o);
  const TriangleMesh s1 = TrueWall(MakeScan(a, Posture::Supine, o), o);
  const TriangleMesh s2 = TrueWall(MakeScan(MakeAnatomy(o), Posture::Supine, o), o);
  const TriangleMesh p1 = TrueWall(MakeScan(a, Posture::Prone, o), o);
  EXPECT_TRUE(s1.V == s2.V);
  EXPECT_TRUE(s1.F == s2.F);
  EXPECT_TRUE(s1.F == p1.F);
  EXPECT_FALSE(s1.V == p1.V);
  o.seed = 4;
  const TriangleMesh other = TrueWall(MakeScan(MakeAnatomy(o), Posture::Supine, o), o);
  EXPECT_FALSE(other.V.rows() == s1.V.rows() && other.V == s1.V);
}

TEST(PhantomMesh, FaceDilatationOfKnownAffineMaps) {
  TriangleMesh a, b;
  a.V.resize(3, 3);
  a.V << 0, 0, 0, 1, 0, 0, 0, 1, 0;
  a.F.resize(1, 3);
  a.F << 0, 1, 2;
  b = a;
  b.V.col(0) *= 2.0;  // stretch x by 2 -> K = 2
  EXPECT_NEAR(FaceDilatation(a, b)[0], 2.0, 1e-12);
  // A rotation into another plane and uniform scaling are conformal: K = 1.
  b.V << 0, 0, 5, 0, 3, 5, 0, 0, 8;
  EXPECT_NEAR(FaceDilatation(a, b)[0], 1.0, 1e-12);
  // Shear x += y: singular values of [[1,1],[0,1]] -> K = (3 + sqrt 5) / 2.
  b.V << 0, 0, 0, 1, 0, 0, 1, 1, 0;
  EXPECT_NEAR(FaceDilatation(a, b)[0], (3.0 + std::sqrt(5.0)) / 2.0, 1e-12);
  b.F << 0, 2, 1;
  EXPECT_THROW(FaceDilatation(a, b), std::invalid_argument);
}

TEST(PhantomMesh, DilatationNoneAtZeroDeformationAndInRangeOtherwise) {
  PhantomOptions o = CoarseOptions(1, 0.0);
  o.meshPointsAround = 128;
  DilatationStats stats[3];
  const double defs[3] = {0.0, 0.5, 1.0};
  for (int d = 0; d < 3; ++d) {
    o.deformation = defs[d];
    const ColonAnatomy a = MakeAnatomy(o);
    const TriangleMesh ws = TrueWall(MakeScan(a, Posture::Supine, o), o), wp = TrueWall(MakeScan(a, Posture::Prone, o), o);
    stats[d] = SummarizeDilatation(FaceDilatation(ws, wp), FaceSegments(ws));
  }
  EXPECT_LT(stats[0].all.max, 1.0 + 1e-6);
  // Default deformation: clearly non-conformal, mostly 1.1-3.
  EXPECT_GT(stats[1].all.median, 1.1);
  EXPECT_LT(stats[1].all.p90, 2.5);
  EXPECT_LT(stats[1].all.max, 12.0);
  // Strong deformation: p90 towards 3, peaks of several.
  EXPECT_GT(stats[2].all.p90, stats[1].all.p90 + 0.3);
  EXPECT_GT(stats[2].all.p90, 2.0);
  EXPECT_LT(stats[2].all.p90, 3.6);
  EXPECT_GT(stats[2].all.max, 4.0);
  EXPECT_LT(stats[2].all.max, 40.0);
  // Mobile segments deform more than the fixed ones.
  EXPECT_GT(stats[2].segment[kTransverse].median, stats[2].segment[kDescending].median);
  EXPECT_GT(stats[2].segment[kSigmoid].median, stats[2].segment[kDescending].median);
  for (int g = 0; g < 5; ++g) EXPECT_GT(stats[1].segment[g].count, 1000u);
}
