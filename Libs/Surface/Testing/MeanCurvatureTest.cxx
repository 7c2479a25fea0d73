// Cotangent Laplacian and mean curvature on shapes with known curvature.
#include "Surface/MeanCurvature.h"
#include "Surface/MeshTopology.h"
#include "TestShapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::surface {
namespace {

constexpr double kPi = 3.14159265358979323846;

TEST(MeanCurvature, SphereIsOneOverRadius) {
  for (double r : {2.0, 15.0}) {
    const TriangleMesh s = testing::Icosphere(r, 4);
    const Eigen::VectorXd H = MeanCurvature(s.V, s.F);
    EXPECT_NEAR(H.minCoeff(), 1.0 / r, 0.03 / r);
    EXPECT_NEAR(H.maxCoeff(), 1.0 / r, 0.03 / r);
    // Mixed areas sum to the area of the polyhedron (slightly below 4 pi r^2).
    const double area = MixedVertexAreas(s.V, s.F).sum();
    EXPECT_NEAR(area, 4 * kPi * r * r, 0.01 * 4 * kPi * r * r);
    // Flipped orientation flips the sign.
    Eigen::MatrixXi flipped = s.F;
    flipped.col(1).swap(flipped.col(2));
    EXPECT_NEAR(MeanCurvature(s.V, flipped).mean(), -1.0 / r, 0.03 / r);
  }
}

TEST(MeanCurvature, LaplacianIsSymmetricWithZeroRowSums) {
  const TriangleMesh t = testing::Torus(10.0, 3.0, 40, 16);
  const Eigen::SparseMatrix<double> L = CotangentLaplacian(t.V, t.F);
  const Eigen::SparseMatrix<double> D = L - Eigen::SparseMatrix<double>(L.transpose());
  EXPECT_LT(D.norm(), 1e-9 * L.norm());
  EXPECT_LT((L * Eigen::VectorXd::Ones(L.rows())).cwiseAbs().maxCoeff(), 1e-9);
  // Linear functions are harmonic away from the boundary on a closed mesh only approximately,
  // but x . L x = -2 * Dirichlet energy is negative.
  const Eigen::VectorXd x = t.V.col(0);
  EXPECT_LT(x.dot(L * x), 0.0);
}

TEST(MeanCurvature, TorusMatchesTheFormula) {
  const double R = 10.0, a = 3.0;
  const int n = 120, m = 48;
  const TriangleMesh t = testing::Torus(R, a, n, m);
  const Eigen::VectorXd H = MeanCurvature(t.V, t.F);
  double worst = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double w = 2 * kPi * j / m;
      const double truth = (R + 2 * a * std::cos(w)) / (2 * a * (R + a * std::cos(w)));
      worst = std::max(worst, std::abs(H(i * m + j) - truth));
    }
  EXPECT_LT(worst, 0.03 / a);
}

TEST(MeanCurvature, CylinderInteriorIsHalfOverRadius) {
  const double r = 5.0;
  const TriangleMesh c = testing::OpenCylinder(r, 20.0, 64, 40);
  const Eigen::VectorXd H = MeanCurvature(c.V, c.F);
  for (Eigen::Index v = 0; v < c.V.rows(); ++v) {
    const double z = c.V(v, 2);
    if (z < 1.0 || z > 19.0) continue;  // boundary rings have no full one-ring
    EXPECT_NEAR(H(v), 0.5 / r, 0.03 / r);
  }
}

TEST(MeanCurvature, VertexNormalsPointOutOfTheSphere) {
  const TriangleMesh s = testing::Icosphere(3.0, 2);
  const Eigen::MatrixXd N = VertexNormals(s.V, s.F);
  for (Eigen::Index v = 0; v < s.V.rows(); ++v) EXPECT_GT(N.row(v).dot(s.V.row(v).normalized()), 0.99);
}

}  // namespace
}  // namespace colonmap::surface
