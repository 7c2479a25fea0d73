// Topology utilities on shapes with known answers.
#include "Surface/MeshTopology.h"
#include "TestShapes.h"

#include <gtest/gtest.h>

namespace colonmap::surface {
namespace {

using testing::Icosphere;
using testing::OpenCylinder;
using testing::Torus;

TEST(MeshTopology, SphereIsClosedGenusZero) {
  const TriangleMesh s = Icosphere(10.0, 3);
  const TopologyReport r = AnalyzeTopology(s.F);
  EXPECT_EQ(r.euler, 2);
  EXPECT_EQ(EulerCharacteristic(s.F), 2);
  EXPECT_EQ(r.components, 1);
  EXPECT_EQ(r.boundaryLoops, 0);
  EXPECT_EQ(r.nonManifoldEdges, 0);
  EXPECT_EQ(r.nonManifoldVertices, 0);
  EXPECT_EQ(r.inconsistentEdges, 0);
  EXPECT_EQ(r.Genus(), 0);
  EXPECT_TRUE(r.IsClosedGenusZero());
  EXPECT_EQ(r.edges, 3 * r.faces / 2);
}

TEST(MeshTopology, TorusHasEulerZero) {
  const TopologyReport r = AnalyzeTopology(Torus(10.0, 3.0, 40, 16).F);
  EXPECT_EQ(r.euler, 0);
  EXPECT_EQ(r.Genus(), 1);
  EXPECT_EQ(r.boundaryLoops, 0);
  EXPECT_FALSE(r.IsClosedGenusZero());
}

TEST(MeshTopology, OpenCylinderHasTwoBoundaryLoops) {
  const int n = 24, m = 10;
  const TriangleMesh c = OpenCylinder(5.0, 20.0, n, m);
  const auto loops = BoundaryLoops(c.F);
  ASSERT_EQ(loops.size(), 2u);
  for (const auto& loop : loops) {
    EXPECT_EQ(loop.size(), std::size_t(n));
    // Each loop lies on one end ring.
    const double z = c.V(loop[0], 2);
    for (int v : loop) EXPECT_DOUBLE_EQ(c.V(v, 2), z);
  }
  const TopologyReport r = AnalyzeTopology(c.F);
  EXPECT_EQ(r.euler, 0);
  EXPECT_EQ(r.Genus(), 0);
  EXPECT_EQ(r.boundaryLoops, 2);
}

TEST(MeshTopology, ComponentsAreOrderedBySize) {
  const TriangleMesh big = Icosphere(10.0, 2), small = Icosphere(1.0, 1);
  Eigen::MatrixXi F(big.F.rows() + small.F.rows(), 3);
  // Small sphere first, so that the order by size differs from the order of faces.
  F << small.F, (big.F.array() + int(small.V.rows())).matrix();
  int count = 0;
  const std::vector<int> c = FaceComponents(F, &count);
  ASSERT_EQ(count, 2);
  EXPECT_EQ(c.front(), 1);
  EXPECT_EQ(c.back(), 0);
  const std::vector<int> sizes = ComponentSizes(c, count);
  EXPECT_EQ(sizes[0], big.F.rows());
  EXPECT_EQ(sizes[1], small.F.rows());
  EXPECT_EQ(EulerCharacteristic(F), 4);
  EXPECT_EQ(AnalyzeTopology(F).Genus(), -1);  // undefined for two components

  Eigen::MatrixXd V(big.V.rows() + small.V.rows(), 3), Vk;
  V << small.V, big.V;
  Eigen::MatrixXi Fk;
  std::vector<bool> keep(c.size());
  for (std::size_t f = 0; f < c.size(); ++f) keep[f] = c[f] == 0;
  std::vector<int> old;
  KeepFaces(V, F, keep, Vk, Fk, &old);
  EXPECT_EQ(Vk.rows(), big.V.rows());
  EXPECT_EQ(Fk, big.F);
  EXPECT_EQ(old.front(), int(small.V.rows()));
}

TEST(MeshTopology, FindsNonManifoldEdgesAndVertices) {
  // Three triangles sharing edge (0, 1).
  Eigen::MatrixXi F(3, 3);
  F << 0, 1, 2, 1, 0, 3, 0, 1, 4;
  const auto e = NonManifoldEdges(F);
  ASSERT_EQ(e.size(), 1u);
  EXPECT_EQ(e[0][0], 0);
  EXPECT_EQ(e[0][1], 1);
  // Two closed tetrahedra touching at vertex 0: a non-manifold vertex, no bad edge.
  Eigen::MatrixXi T(8, 3);
  T << 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2,   // tetra 0,1,2,3
      0, 5, 4, 0, 4, 6, 4, 5, 6, 0, 6, 5;    // tetra 0,4,5,6
  EXPECT_TRUE(NonManifoldEdges(T).empty());
  const auto v = NonManifoldVertices(T);
  ASSERT_EQ(v.size(), 1u);
  EXPECT_EQ(v[0], 0);
  EXPECT_EQ(InconsistentlyOrientedEdges(T), 0);
  EXPECT_FALSE(AnalyzeTopology(T).IsClosedGenusZero());
  EXPECT_EQ(EulerCharacteristic(T), 3);
  // Splitting the shared vertex gives two closed genus-0 tetrahedra.
  Eigen::MatrixXd V = Eigen::MatrixXd::Random(7, 3);
  EXPECT_EQ(SplitNonManifoldVertices(V, T), 1);
  EXPECT_EQ(V.rows(), 8);
  EXPECT_EQ(V.row(7), V.row(0));
  EXPECT_TRUE(NonManifoldVertices(T).empty());
  EXPECT_EQ(EulerCharacteristic(T), 4);
  EXPECT_EQ(AnalyzeTopology(T).components, 2);
}

TEST(MeshTopology, DetectsInconsistentOrientation) {
  TriangleMesh s = Icosphere(1.0, 1);
  EXPECT_EQ(InconsistentlyOrientedEdges(s.F), 0);
  std::swap(s.F(0, 1), s.F(0, 2));  // flip one face: its three edges disagree with neighbours
  EXPECT_EQ(InconsistentlyOrientedEdges(s.F), 3);
  EXPECT_FALSE(AnalyzeTopology(s.F).IsClosedGenusZero());
}

}  // namespace
}  // namespace colonmap::surface
