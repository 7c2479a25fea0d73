// Textures on the 3D surface (SurfaceTextures.h, SurfaceScene.h): the texture lookup a renderer
// does (tile pixel at the repeating texture coordinate) shows the same value as the flat
// definitions CheckerboardAt / CirclesAt at the vertex's flat coordinates; seam faces are split
// so no face's texture coordinates span more than half a period; per-face colours are the
// colour map's (the colour bar's) colours; vertex normals of a known surface.
#include "Views/SurfaceScene.h"
#include "Views/SurfaceTextures.h"

#include "Core/Error.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace colonmap;
using namespace colonmap::views;

namespace {

// Nearest-pixel repeating lookup, what vtkTexture with InterpolateOff and RepeatOn does.
double Lookup(const TextureTile& t, double s, double tt) {
  const double fs = s - std::floor(s), ft = tt - std::floor(tt);
  const int x = std::min(t.image.width - 1, static_cast<int>(fs * t.image.width));
  const int y = std::min(t.image.height - 1, static_cast<int>(ft * t.image.height));
  return t.image.At(x, y)[0] / 255.0;
}

// A cylinder of radius 10 around z, `around` x `along` vertices, uv periodic in u (width w):
// faces close the loop, so those across u = 0 are seam faces.
void Cylinder(int around, int along, double w, Eigen::MatrixXd& V, Eigen::MatrixXi& F, Eigen::MatrixXd& uv) {
  V.resize(around * along, 3);
  uv.resize(around * along, 2);
  F.resize(2 * around * (along - 1), 3);
  for (int j = 0; j < along; ++j)
    for (int i = 0; i < around; ++i) {
      const double a = 2 * M_PI * i / around;
      V.row(j * around + i) << 10 * std::cos(a), 10 * std::sin(a), 5.0 * j;
      uv.row(j * around + i) << w * i / around, 0.1 * j;
    }
  int f = 0;
  for (int j = 0; j + 1 < along; ++j)
    for (int i = 0; i < around; ++i) {
      const int a = j * around + i, b = j * around + (i + 1) % around, c = a + around, d = b + around;
      F.row(f++) << a, b, d;
      F.row(f++) << a, d, c;
    }
}

}  // namespace

TEST(SurfaceTextures, TileLookupEqualsTheFlatTextureDefinitions) {
  const TextureOptions o;
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0, 1), v(0, 3);
  for (SurfaceTextureKind kind : {SurfaceTextureKind::Checkerboard, SurfaceTextureKind::Circles}) {
    const TextureTile tile = MakeTextureTile(kind, o, 32);
    for (double width : {1.0, 0.7}) {
      Eigen::MatrixXd uv(2000, 2);
      for (Eigen::Index i = 0; i < uv.rows(); ++i) uv.row(i) << width * u(rng), v(rng);
      const Eigen::VectorXd truth = kind == SurfaceTextureKind::Checkerboard ? CheckerboardAt(uv, width, o) : CirclesAt(uv, width, o);
      const TexturedMesh m = TextureCoordinates(Eigen::MatrixXd::Zero(uv.rows(), 3), Eigen::MatrixXi(0, 3), uv,
                                                Eigen::VectorXd::Constant(uv.rows(), width), tile, o);
      int wrong = 0;
      for (Eigen::Index i = 0; i < uv.rows(); ++i) wrong += Lookup(tile, m.st(i, 0), m.st(i, 1)) != truth(i);
      // Only points within a tile pixel of an edge may differ (pixel = 1/32 cell).
      EXPECT_LT(wrong, 0.06 * uv.rows()) << static_cast<int>(kind) << " width " << width;
    }
  }
  // Fraction of black in the circles tile: 1 - pi r^2 (r = 0.35 cell).
  const TextureTile c = MakeTextureTile(SurfaceTextureKind::Circles, o, 64);
  double white = 0;
  for (int y = 0; y < c.image.height; ++y)
    for (int x = 0; x < c.image.width; ++x) white += c.image.At(x, y)[0] / 255.0;
  EXPECT_NEAR(white / (c.image.width * c.image.height), M_PI * 0.35 * 0.35, 0.01);
}

TEST(SurfaceTextures, SeamFacesGetShiftedCopiesAndKeepTheirTexture) {
  Eigen::MatrixXd V, uv;
  Eigen::MatrixXi F;
  const double width = 1.0;
  Cylinder(16, 5, width, V, F, uv);
  const TextureOptions o;
  const TextureTile tile = MakeTextureTile(SurfaceTextureKind::Checkerboard, o, 8);
  const TexturedMesh m = TextureCoordinates(V, F, uv, Eigen::VectorXd::Constant(V.rows(), width), tile, o);
  ASSERT_EQ(m.F.rows(), F.rows());
  // One tile = 2 cells = width / 4; a period is 4 tiles.
  const double period = 4.0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    double lo = 1e9, hi = -1e9;
    for (int k = 0; k < 3; ++k) {
      lo = std::min(lo, m.st(m.F(f, k), 0));
      hi = std::max(hi, m.st(m.F(f, k), 0));
      EXPECT_EQ(m.source(m.F(f, k)), F(f, k));  // same corner (or a copy of it)
      EXPECT_EQ(m.V.row(m.F(f, k)), V.row(F(f, k)));
    }
    EXPECT_LT(hi - lo, 0.5 * period) << "face " << f;
  }
  // The seam column of vertices (u = 0) is copied once (shift +1 period): 5 copies.
  EXPECT_EQ(m.V.rows(), V.rows() + 5);
  for (Eigen::Index i = V.rows(); i < m.V.rows(); ++i) {
    const int s = m.source(i);
    EXPECT_NEAR(m.st(i, 0) - m.st(s, 0), period, 1e-12);
    EXPECT_EQ(Lookup(tile, m.st(i, 0), m.st(i, 1) + 0.01), Lookup(tile, m.st(s, 0), m.st(s, 1) + 0.01));
  }
  TextureOptions odd;
  odd.cellsAcross = 7;
  EXPECT_THROW(TextureCoordinates(V, F, uv, Eigen::VectorXd::Constant(V.rows(), width), tile, odd), Error);
  EXPECT_THROW(TextureCoordinates(V, F, uv.topRows(3), Eigen::VectorXd::Constant(V.rows(), width), tile, o), Error);
}

TEST(SurfaceScene, FaceColoursAreTheColourMapsAndNormalsPointOutOfTheCylinder) {
  Eigen::MatrixXd V, uv;
  Eigen::MatrixXi F;
  Cylinder(24, 4, 1.0, V, F, uv);
  Eigen::VectorXd K(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) K(f) = 1.0 + 0.01 * f;
  K(3) = std::numeric_limits<double>::quiet_NaN();
  K(5) = std::numeric_limits<double>::infinity();
  K(6) = 0.5;  // below the range: clamped to the low end
  const SurfaceScene s = ColouredSurface(V, F, K, 1.0, 1.5, ColourMapKind::Turbo, {1, 2, 3});
  ASSERT_EQ(s.faceColours.size(), static_cast<std::size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (f == 3) continue;  // (5: infinite, ColourOf gives the NaN colour too)
    EXPECT_EQ(s.faceColours[f], ColourOf(K(f), 1.0, 1.5, ColourMapKind::Turbo, {1, 2, 3}));
  }
  EXPECT_EQ(s.faceColours[3], (Bgr{1, 2, 3}));
  EXPECT_EQ(s.faceColours[5], (Bgr{1, 2, 3}));
  EXPECT_NE(s.faceColours[0], s.faceColours[F.rows() - 1]);  // low and high ends differ
  // Normals are radial (faces wound counter-clockwise seen from outside): cos > 0.95 with the
  // radial direction at every vertex, |n| = 1.
  for (Eigen::Index i = 0; i < V.rows(); ++i) {
    const Eigen::Vector3d radial = Eigen::Vector3d(V(i, 0), V(i, 1), 0).normalized();
    EXPECT_NEAR(s.normals.row(i).norm(), 1.0, 1e-12);
    EXPECT_GT(std::abs(s.normals.row(i).dot(radial)), 0.95) << i;
  }
  EXPECT_THROW(ColouredSurface(V, F, K.head(3), 1, 2, ColourMapKind::Turbo), Error);
}
