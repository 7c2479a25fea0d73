// RepairSurfaceFlips on a known case: a target whose flat -> 3D map is orientation-preserving on
// every triangle (identity left of u = 0, the shear (u, v) -> (u, v + 5u) right of it, det 1)
// still reverses the straight 3D triangle through the images of a source face that straddles the
// crease. Moving the one interior source vertex must remove the reversal without reversing any
// flat face and without moving the source's boundary.
#include "Registration/SurfaceFlipRepair.h"

#include "Flattening/BeltramiCoefficient.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::registration {
namespace {

Eigen::Vector3d Sheared(const Eigen::Vector2d& p) { return {p.x(), p.y() + (p.x() > 0 ? 5.0 * p.x() : 0.0), 0.0}; }

// Target: a grid over [-1, 1]^2 with a grid line on u = 0 (so the crease runs along edges).
FlatSegment ShearedTarget(int cells) {
  FlatSegment t;
  const int n = cells + 1;
  t.uv.resize(n * n, 2);
  t.position.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d p(-1.0 + 2.0 * i / cells, -1.0 + 2.0 * j / cells);
      t.uv.row(j * n + i) = p.transpose();
      t.position.row(j * n + i) = Sheared(p).transpose();
    }
  t.F.resize(2 * cells * cells, 3);
  int f = 0;
  for (int j = 0; j < cells; ++j)
    for (int i = 0; i < cells; ++i) {
      const int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      t.F.row(f++) << a, b, d;
      t.F.row(f++) << a, d, c;
    }
  return t;
}

struct Fan {
  Eigen::MatrixXd image;  // flat images (the identity into the target's flat domain)
  Eigen::MatrixXi F;
};

// A hexagon fan of radius r around the origin, counter-clockwise.
Fan HexagonFan(double r) {
  Fan s;
  s.image.resize(7, 2);
  s.image.row(0) << 0.0, 0.0;
  for (int k = 0; k < 6; ++k) s.image.row(1 + k) << r * std::cos(M_PI / 3 * k), r * std::sin(M_PI / 3 * k);
  s.F.resize(6, 3);
  for (int k = 0; k < 6; ++k) s.F.row(k) << 0, 1 + k, 1 + (k + 1) % 6;
  return s;
}

int Reversed3D(const Fan& s, const Eigen::MatrixXd& position, const Eigen::MatrixXd& normal) {
  int bad = 0;
  for (Eigen::Index f = 0; f < s.F.rows(); ++f) bad += !ImageFacesAlongSurface(s.F, f, position, normal);
  return bad;
}

Eigen::MatrixXd Positions(const Eigen::MatrixXd& image) {
  Eigen::MatrixXd p(image.rows(), 3);
  for (Eigen::Index i = 0; i < image.rows(); ++i) p.row(i) = Sheared(image.row(i).transpose()).transpose();
  return p;
}

TEST(SurfaceFlipRepair, MovesTheInteriorVertexOffAStraddlingReversal) {
  const FlatSegment target = ShearedTarget(40);
  const Eigen::MatrixXd targetNormals = Eigen::MatrixXd::Zero(target.uv.rows(), 3).rowwise() + Eigen::RowVector3d(0, 0, 1);
  Fan s = HexagonFan(0.1);
  const Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(7, 3).rowwise() + Eigen::RowVector3d(0, 0, 1);
  ASSERT_EQ((flattening::SignedFlatAreas(s.image, s.F).array() <= 0).count(), 0);
  std::vector<Eigen::Index> bad;
  const Eigen::MatrixXd before = Positions(s.image);
  for (Eigen::Index f = 0; f < s.F.rows(); ++f)
    if (!ImageFacesAlongSurface(s.F, f, before, normal)) bad.push_back(f);
  ASSERT_EQ(bad.size(), 1u);  // the face across the crease below the centre

  const Eigen::MatrixXd ring = s.image.bottomRows(6);
  const Eigen::Vector2d centre = s.image.row(0).transpose();
  EXPECT_EQ(RepairSurfaceFlips(s.image, s.F, target, targetNormals, before, normal, bad), 1);
  EXPECT_EQ(Reversed3D(s, Positions(s.image), normal), 0);
  EXPECT_EQ((flattening::SignedFlatAreas(s.image, s.F).array() <= 0).count(), 0);
  EXPECT_EQ((s.image.bottomRows(6) - ring).norm(), 0.0);  // the fan's boundary stays
  EXPECT_GT((s.image.row(0).transpose() - centre).norm(), 0.0);
  EXPECT_LT((s.image.row(0).transpose() - centre).norm(), 0.1);
}

TEST(SurfaceFlipRepair, LeavesAFaceThatFacesRightAlone) {
  const FlatSegment target = ShearedTarget(20);
  const Eigen::MatrixXd targetNormals = Eigen::MatrixXd::Zero(target.uv.rows(), 3).rowwise() + Eigen::RowVector3d(0, 0, 1);
  Fan s = HexagonFan(0.1);
  s.image.rowwise() -= Eigen::RowVector2d(0.5, 0.0);  // wholly left of the crease: identity
  const Eigen::MatrixXd position = Positions(s.image), normal = Eigen::MatrixXd::Zero(7, 3).rowwise() + Eigen::RowVector3d(0, 0, 1);
  const Eigen::MatrixXd image = s.image;
  EXPECT_EQ(RepairSurfaceFlips(s.image, s.F, target, targetNormals, position, normal, {0, 1, 2}), 0);
  EXPECT_EQ((s.image - image).norm(), 0.0);
}

}  // namespace
}  // namespace colonmap::registration
