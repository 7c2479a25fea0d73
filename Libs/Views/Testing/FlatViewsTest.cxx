// Unit tests of the flat and distortion views (issue 8) with known answers: identity and affine
// registrations of an analytic flat picture, a known cyclic shift recovered, the periodic cut,
// colour bar ends, textures, statistics, morph frames, segment extraction, composition.
#include "Views/ColourMap.h"
#include "Views/DistortionStatistics.h"
#include "Views/DistortionTextures.h"
#include "Views/FlatComposition.h"
#include "Views/FlatImageCorrelation.h"
#include "Views/FlatResampling.h"
#include "Views/FlatSegmentMesh.h"
#include "Views/MorphSequence.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using namespace colonmap;
using namespace colonmap::views;

constexpr double kPi = 3.14159265358979323846;

// A flat rectangle [0, width] x [0, height] triangulated on an (nu + 1) x (nv + 1) vertex grid;
// the column u = width is the cut's second copy of u = 0 (periodic strip).
struct FlatRect {
  Eigen::MatrixXd uv;
  Eigen::MatrixXi F;
};

FlatRect MakeRect(double width, double height, int nu, int nv) {
  FlatRect r;
  r.uv.resize((nu + 1) * (nv + 1), 2);
  for (int j = 0; j <= nv; ++j)
    for (int i = 0; i <= nu; ++i) r.uv.row(j * (nu + 1) + i) << width * i / nu, height * j / nv;
  r.F.resize(2 * nu * nv, 3);
  int f = 0;
  for (int j = 0; j < nv; ++j)
    for (int i = 0; i < nu; ++i) {
      const int a = j * (nu + 1) + i, b = a + 1, c = a + nu + 1, d = c + 1;
      r.F.row(f++) << a, b, d;
      r.F.row(f++) << a, d, c;
    }
  return r;
}

// A smooth picture periodic in u (mm): what a curvature image of the prone scan could be.
double Pattern(double uMm, double vMm, double widthMm) {
  return std::sin(2 * kPi * uMm / widthMm) + 0.5 * std::cos(2 * kPi * vMm / 37.0) + 0.3 * std::sin(2 * kPi * (uMm / widthMm + vMm / 53.0));
}

// The picture as ColonFlattening writes it: nx x ny pixels over [0, widthMm] x [0, heightMm].
Volume<float> PatternImage(double widthMm, double heightMm, int nx, int ny) {
  Volume<float> im;
  im.size = {static_cast<std::size_t>(nx), static_cast<std::size_t>(ny), 1};
  im.spacing = Eigen::Vector3d(widthMm / nx, heightMm / ny, 1.0);
  im.origin = Eigen::Vector3d(0.5 * im.spacing.x(), 0.5 * im.spacing.y(), 0.0);
  im.Allocate(0.0f);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      im.At(i, j, 0) = static_cast<float>(Pattern((i + 0.5) * im.spacing.x(), (j + 0.5) * im.spacing.y(), widthMm));
  return im;
}

TEST(FlatResampling, IdentityRegistrationGivesTheSamePicture) {
  const FlatRect s = MakeRect(1.0, 2.0, 24, 40);
  const double toMm = 150.0;  // mm per flat unit
  const Volume<float> image = PatternImage(150.0, 300.0, 150, 300);
  const FlatGrid grid = GridFor(1.0, 2.0, 64.0);
  NullProgress progress;
  const FlatPixelHits hits = LocatePixels(s.uv, s.F, 1.0, grid, 1e-6, progress);
  EXPECT_EQ((hits.face.array() < 0).count(), 0);
  const Eigen::MatrixXd mapped = MapPixels(hits, s.F, s.uv, 1.0);
  const Eigen::VectorXf registered = SampleFlatImage(image, mapped, toMm, true);
  const Eigen::VectorXf direct = SampleFlatImage(image, grid.Centres(), toMm, true);
  ASSERT_EQ(registered.size(), direct.size());
  EXPECT_LT((registered - direct).cwiseAbs().maxCoeff(), 1e-5f);
  EXPECT_GT(FlatImageCorrelation(registered, direct).r, 0.999999);
}

TEST(FlatResampling, KnownAffineRegistrationSamplesTheRightPlace) {
  // Prone = eta(supine): u shifted by 0.3 (wrapping across the cut), v scaled by 1.25. The
  // target coordinates are wrapped into [0, 1), so faces near u = 0.7 straddle the prone cut.
  const FlatRect s = MakeRect(1.0, 2.0, 30, 50);
  Eigen::MatrixXd target(s.uv.rows(), 2);
  for (Eigen::Index k = 0; k < s.uv.rows(); ++k) {
    const double u = s.uv(k, 0) + 0.3;
    target.row(k) << u - std::floor(u), 1.25 * s.uv(k, 1);
  }
  const double widthMm = 140.0, toMm = 140.0;
  const Volume<float> prone = PatternImage(widthMm, 2.5 * toMm, 280, 700);
  const FlatGrid grid = GridFor(1.0, 2.0, 50.0);
  NullProgress progress;
  const FlatPixelHits hits = LocatePixels(s.uv, s.F, 1.0, grid, 1e-6, progress);
  const Eigen::MatrixXd mapped = MapPixels(hits, s.F, target, 1.0);
  const Eigen::VectorXf sampled = SampleFlatImage(prone, mapped, toMm, true);
  const Eigen::MatrixXd c = grid.Centres();
  double worst = 0;
  for (Eigen::Index p = 0; p < c.rows(); ++p) {
    // The map is affine, so the interpolated image is exact up to the periodic wrap.
    const double u = c(p, 0) + 0.3, v = 1.25 * c(p, 1);
    EXPECT_NEAR(std::fmod(mapped(p, 0) - u + 10.0, 1.0) < 0.5 ? std::fmod(mapped(p, 0) - u + 10.0, 1.0)
                                                               : std::fmod(mapped(p, 0) - u + 10.0, 1.0) - 1.0,
                0.0, 1e-9);
    EXPECT_NEAR(mapped(p, 1), v, 1e-9);
    worst = std::max(worst, std::fabs(sampled(p) - Pattern(u * toMm, v * toMm, widthMm)));
  }
  // Bilinear sampling of a 0.5 mm picture of a pattern with ~37 mm periods: small error.
  EXPECT_LT(worst, 0.01);
}

TEST(FlatResampling, KnownShiftIsRecoveredByTheRegisteredPicture) {
  // Prone anatomy = supine anatomy moved by 0.2 around (a different cut position): the prone
  // picture at (u + 0.2, v) shows what the supine picture shows at (u, v). Registered with that
  // shift the prone picture equals the supine one; unregistered it does not.
  const double widthMm = 120.0, heightMm = 240.0, toMm = 120.0;
  const int nx = 240, ny = 480;
  const Volume<float> supine = PatternImage(widthMm, heightMm, nx, ny);
  Volume<float> prone = supine;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) prone.At((i + 48) % nx, j, 0) = supine.At(i, j, 0);  // 48 px = 0.2
  const FlatRect s = MakeRect(1.0, 2.0, 20, 40);
  Eigen::MatrixXd target = s.uv;
  target.col(0).array() += 0.2;
  const FlatGrid grid = GridFor(1.0, 2.0, 60.0);
  NullProgress progress;
  const FlatPixelHits hits = LocatePixels(s.uv, s.F, 1.0, grid, 1e-6, progress);
  const Eigen::VectorXf sup = SampleFlatImage(supine, grid.Centres(), toMm, true);
  const Eigen::VectorXf reg = SampleFlatImage(prone, MapPixels(hits, s.F, target, 1.0), toMm, true);
  const Eigen::VectorXf unreg = SampleFlatImage(prone, grid.Centres(), toMm, true);
  const double rReg = FlatImageCorrelation(sup, reg).r, rUnreg = FlatImageCorrelation(sup, unreg).r;
  EXPECT_GT(rReg, 0.9999);
  EXPECT_LT(rUnreg, 0.9);
  EXPECT_LT((sup - reg).cwiseAbs().maxCoeff(), 1e-4f);
}

TEST(FlatResampling, OutsideTheDomainIsNaN) {
  const FlatRect s = MakeRect(1.0, 1.0, 8, 8);
  FlatGrid grid;
  grid.nx = 10;
  grid.ny = 20;
  grid.width = 1.0;
  grid.height = 2.0;  // the upper half lies beyond the mesh
  NullProgress progress;
  const FlatPixelHits hits = LocatePixels(s.uv, s.F, 1.0, grid, 1e-6, progress);
  const Eigen::MatrixXd mapped = MapPixels(hits, s.F, s.uv, 1.0);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) {
      const Eigen::Index p = j * grid.nx + i;
      EXPECT_EQ(hits.face(p) >= 0, j < 10) << i << " " << j;
      EXPECT_EQ(std::isnan(mapped(p, 0)), j >= 10);
    }
  // Per-face values land on the pixels of their faces.
  Eigen::VectorXd values = Eigen::VectorXd::LinSpaced(s.F.rows(), 0.0, s.F.rows() - 1.0);
  const Eigen::VectorXd at = FaceValuesAtPixels(hits, values);
  for (Eigen::Index p = 0; p < at.size(); ++p)
    if (hits.face(p) >= 0) EXPECT_EQ(at(p), hits.face(p));
    else EXPECT_TRUE(std::isnan(at(p)));
  // Picture rows: row 0 is the top (largest v).
  Eigen::VectorXf pv(grid.nx * grid.ny);
  for (int j = 0; j < grid.ny; ++j)
    for (int i = 0; i < grid.nx; ++i) pv(j * grid.nx + i) = static_cast<float>(j);
  const Eigen::MatrixXf pic = PixelsToPicture(pv, grid);
  EXPECT_EQ(pic(0, 3), grid.ny - 1);
  EXPECT_EQ(pic(grid.ny - 1, 3), 0);
}

TEST(FlatImageCorrelation, KnownAnswers) {
  Eigen::VectorXf a(6), b(6);
  a << 1, 2, 3, 4, 5, std::nanf("");
  b = 2 * a.array() + 1;
  EXPECT_NEAR(FlatImageCorrelation(a, b).r, 1.0, 1e-12);
  EXPECT_EQ(FlatImageCorrelation(a, b).pixels, 5);
  EXPECT_NEAR(FlatImageCorrelation(a, -b).r, -1.0, 1e-12);
  Eigen::VectorXf c = Eigen::VectorXf::Constant(6, 3.0f);
  EXPECT_EQ(FlatImageCorrelation(a, c).r, 0.0);
}

TEST(ColourMap, BarEndsMapToLowAndHigh) {
  for (ColourMapKind kind : {ColourMapKind::Turbo, ColourMapKind::Hsv, ColourMapKind::Grey}) {
    ColourBarLayout l;
    const ColourImage bar = ColourBar(300, 1.0, 2.5, kind, "K", 4, "%.2f", &l);
    EXPECT_EQ(bar.height, 300);
    const int x = l.barX + l.barWidth / 2;
    EXPECT_EQ(bar.At(x, l.barTop), ColourOf(2.5, 1.0, 2.5, kind));
    EXPECT_EQ(bar.At(x, l.barBottom), ColourOf(1.0, 1.0, 2.5, kind));
    // The cyclic map has equal ends by design; the others must tell the ends apart.
    if (kind != ColourMapKind::Hsv) EXPECT_NE(ColourOf(2.5, 1.0, 2.5, kind), ColourOf(1.0, 1.0, 2.5, kind));
  }
  // Values beyond the range are clamped to the end colours; NaN gets the background.
  Eigen::MatrixXf v(1, 4);
  v << 0.0f, 1.0f, 2.5f, std::nanf("");
  const ColourImage im = ColourMapValues(v, 1.0, 2.5, ColourMapKind::Turbo, {7, 8, 9});
  EXPECT_EQ(im.At(0, 0), im.At(1, 0));
  EXPECT_EQ(im.At(2, 0), ColourOf(2.5, 1.0, 2.5, ColourMapKind::Turbo));
  EXPECT_EQ(im.At(3, 0), (Bgr{7, 8, 9}));
  // Grey is the identity ramp.
  EXPECT_EQ(ColourOf(0.5, 0.0, 1.0, ColourMapKind::Grey), (Bgr{128, 128, 128}));
}

TEST(ColourMap, QuantileRangeAndPng) {
  Eigen::MatrixXf a(10, 10);
  for (int k = 0; k < 100; ++k) a.data()[k] = static_cast<float>(k);
  a(0, 0) = std::nanf("");
  const auto r = QuantileRange({&a}, 0.0, 1.0);
  EXPECT_EQ(r[0], 1.0);
  EXPECT_EQ(r[1], 99.0);
  const ColourImage im = ColourMapValues(a, r[0], r[1], ColourMapKind::Turbo);
  const std::vector<std::uint8_t> png = EncodePng(im);
  EXPECT_EQ(png, EncodePng(im));  // deterministic
  const ColourImage back = DecodePng(png);
  EXPECT_EQ(back.width, 10);
  EXPECT_EQ(back.height, 10);
  EXPECT_EQ(back.bgr, im.bgr);  // lossless
}

TEST(FlatComposition, StackAndSideBySideKeepThePictures) {
  const ColourImage a(30, 20, {10, 20, 30}), b(40, 10, {50, 60, 70});
  std::vector<int> y;
  int x0 = 0;
  const ColourImage col = StackColumn({a, b}, {"A", "T"}, "supine", 10, 24, &y, &x0);
  ASSERT_EQ(y.size(), 2u);
  EXPECT_EQ(col.At(x0 + 5, y[0] + 5), (Bgr{10, 20, 30}));
  EXPECT_EQ(col.At(x0 + 35, y[1] + 5), (Bgr{50, 60, 70}));
  EXPECT_EQ(y[1], y[0] + 20 + 10);
  EXPECT_GE(col.width, x0 + 40);
  const ColourImage pair = SideBySide({a, b}, 5);
  EXPECT_EQ(pair.width, 75);
  EXPECT_EQ(pair.height, 20);
  EXPECT_EQ(pair.At(36, 5), (Bgr{50, 60, 70}));
  EXPECT_EQ(pair.At(36, 15), (Bgr{255, 255, 255}));
  // Match colours are distinct and never grey.
  for (int k = 0; k < 12; ++k) {
    const Bgr c = MatchColour(k);
    EXPECT_FALSE(c[0] == c[1] && c[1] == c[2]);
    for (int m = 0; m < k; ++m) EXPECT_NE(c, MatchColour(m));
  }
}

}  // namespace
