// The surface renderer of the 3D pictures (SurfaceRenderer.h, VTK under xvfb-run) on a known
// scene: a flat plate facing the anterior camera. Its silhouette lands where SurfaceCamera's
// projection says (within a pixel), patient's left on the picture's right; a face seen square-on
// shows exactly its colour-map colour (ambient + diffuse = 1 under the headlight); the checkerboard
// texture shows the flat definition's value at the predicted pixels; a posterior camera mirrors
// the picture; renders are byte-identical when repeated.
#include "Views/SurfaceRenderer.h"

#include "Core/Error.h"
#include "Views/DistortionTextures.h"
#include "Views/EndoluminalRenderer.h"  // RenderDisplayAvailable

#include <gtest/gtest.h>

#include <cmath>

using namespace colonmap;
using namespace colonmap::views;

namespace {

constexpr int kW = 120, kH = 160;
const Bgr kWhite{255, 255, 255};

// The plate x in [-50, 50], z in [-100, 100] at y = 0 (facing -y: the anterior camera), nx x nz
// quads of two triangles; uv = ((x + 50) / 100, (z + 100) / 100) (width 1).
void Plate(int nx, int nz, Eigen::MatrixXd& V, Eigen::MatrixXi& F, Eigen::MatrixXd& uv) {
  V.resize((nx + 1) * (nz + 1), 3);
  uv.resize(V.rows(), 2);
  for (int j = 0; j <= nz; ++j)
    for (int i = 0; i <= nx; ++i) {
      const double x = -50 + 100.0 * i / nx, z = -100 + 200.0 * j / nz;
      V.row(j * (nx + 1) + i) << x, 0, z;
      uv.row(j * (nx + 1) + i) << (x + 50) / 100, (z + 100) / 100;
    }
  F.resize(2 * nx * nz, 3);
  int f = 0;
  for (int j = 0; j < nz; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      F.row(f++) << a, b, d;
      F.row(f++) << a, d, c;
    }
}

int Distance(const Bgr& a, const Bgr& b) {
  int d = 0;
  for (int k = 0; k < 3; ++k) d = std::max(d, std::abs(static_cast<int>(a[k]) - static_cast<int>(b[k])));
  return d;
}

SurfaceRenderOptions Small() {
  SurfaceRenderOptions o;
  o.width = kW;
  o.height = kH;
  return o;
}

class SurfaceRendererTest : public ::testing::Test {
 protected:
  void SetUp() override {
    std::string why;
    if (!RenderDisplayAvailable(&why)) GTEST_SKIP() << why;
  }
};

}  // namespace

TEST_F(SurfaceRendererTest, SilhouetteColoursAndOrientationFollowTheCamera) {
  Eigen::MatrixXd V, uv;
  Eigen::MatrixXi F;
  Plate(10, 20, V, F, uv);
  // Faces on the patient's left (x > 0) get the high end of the map, the others the low end.
  Eigen::VectorXd value(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    value(f) = (V(F(f, 0), 0) + V(F(f, 1), 0) + V(F(f, 2), 0)) / 3 > 0 ? 2.0 : 1.0;
  const SurfaceScene scene = ColouredSurface(V, F, value, 1.0, 2.0, ColourMapKind::Turbo);
  const SurfaceCamera cam = FrameSurface(V, SurfaceViewNamed("anterior"), static_cast<double>(kW) / kH, 0.1);
  SurfaceRenderer r(Small());
  const ColourImage im = r.Render(scene, cam);
  ASSERT_EQ(im.width, kW);
  ASSERT_EQ(im.height, kH);
  // Silhouette: bounding box of the non-background pixels against the projected corners.
  int x0 = kW, y0 = kH, x1 = -1, y1 = -1;
  for (int y = 0; y < kH; ++y)
    for (int x = 0; x < kW; ++x)
      if (Distance(im.At(x, y), kWhite) > 30) {
        x0 = std::min(x0, x), y0 = std::min(y0, y), x1 = std::max(x1, x), y1 = std::max(y1, y);
      }
  const Eigen::Vector2d lo = ProjectParallel(cam, kW, kH, Eigen::Vector3d(-50, 0, 100)),
                        hi = ProjectParallel(cam, kW, kH, Eigen::Vector3d(50, 0, -100));
  EXPECT_NEAR(x0, lo.x(), 1.0);
  EXPECT_NEAR(y0, lo.y(), 1.0);
  EXPECT_NEAR(x1 + 1, hi.x(), 1.0);
  EXPECT_NEAR(y1 + 1, hi.y(), 1.0);
  // Square-on faces show their map colour; the patient's left (high end) on the picture's right.
  const Eigen::Vector2d left = ProjectParallel(cam, kW, kH, Eigen::Vector3d(25, 0, 0)),
                        right = ProjectParallel(cam, kW, kH, Eigen::Vector3d(-25, 0, 0));
  EXPECT_GT(left.x(), 0.5 * kW);
  EXPECT_LE(Distance(im.At(static_cast<int>(left.x()), static_cast<int>(left.y())), ColourOf(2.0, 1.0, 2.0, ColourMapKind::Turbo)), 2);
  EXPECT_LE(Distance(im.At(static_cast<int>(right.x()), static_cast<int>(right.y())), ColourOf(1.0, 1.0, 2.0, ColourMapKind::Turbo)), 2);
  // Seen from behind (posterior camera) the halves swap sides.
  const ColourImage back = r.Render(scene, FrameSurface(V, SurfaceViewNamed("posterior"), static_cast<double>(kW) / kH, 0.1));
  EXPECT_LE(Distance(back.At(static_cast<int>(right.x()), static_cast<int>(right.y())), ColourOf(2.0, 1.0, 2.0, ColourMapKind::Turbo)), 2);
  // Determinism.
  const ColourImage again = r.Render(scene, cam);
  EXPECT_EQ(again.bgr, im.bgr);
}

TEST_F(SurfaceRendererTest, CheckerboardTextureShowsTheFlatDefinition) {
  Eigen::MatrixXd V, uv;
  Eigen::MatrixXi F;
  Plate(4, 8, V, F, uv);  // coarse mesh: the texture, not the faces, draws the squares
  const TextureOptions o;  // 8 cells across the width 1 (12.5 mm squares)
  const SurfaceScene scene = TexturedSurface(V, F, uv, Eigen::VectorXd::Constant(V.rows(), 1.0), SurfaceTextureKind::Checkerboard, o);
  const SurfaceCamera cam = FrameSurface(V, SurfaceViewNamed("anterior"), static_cast<double>(kW) / kH, 0.1);
  SurfaceRenderer r(Small());
  const ColourImage im = r.Render(scene, cam);
  // At the centre of every cell the picture is black or white as CheckerboardAt says.
  int checked = 0;
  for (int i = 0; i < 8; ++i)
    for (int j = 0; j < 16; ++j) {
      Eigen::MatrixXd at(1, 2);
      at << (i + 0.5) / 8, (j + 0.5) / 8;
      const double want = CheckerboardAt(at, 1.0, o)(0);
      const Eigen::Vector2d px = ProjectParallel(cam, kW, kH, Eigen::Vector3d(-50 + 100 * at(0, 0), 0, -100 + 100 * at(0, 1)));
      const Bgr c = im.At(static_cast<int>(px.x()), static_cast<int>(px.y()));
      EXPECT_LE(Distance(c, want > 0.5 ? Bgr{255, 255, 255} : Bgr{0, 0, 0}), 3) << i << " " << j;
      ++checked;
    }
  EXPECT_EQ(checked, 128);
}

TEST_F(SurfaceRendererTest, BadSceneThrows) {
  SurfaceRenderer r(Small());
  SurfaceScene s;
  s.V = Eigen::MatrixXd::Zero(3, 3);
  s.F = Eigen::MatrixXi(1, 3);
  s.F << 0, 1, 2;
  s.normals = Eigen::MatrixXd::Zero(3, 3);
  EXPECT_THROW(r.Render(s, SurfaceCamera{}), Error);  // no colours, no texture
  EXPECT_THROW(SurfaceRenderer(SurfaceRenderOptions{8, 8}), Error);
}
