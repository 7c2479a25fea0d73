// The endoluminal renderer (VTK ray casting, under xvfb-run) on a synthetic CT: an air tube in
// soft tissue with a tissue bump on one side. Looking down the tube the centre is dark (far,
// open) and the rim bright (near wall); looking at the wall the centre is bright; the bump shows
// on the side it is on, also when the same physical CT is stored with flipped or left-handed
// axes (direction cosines honoured); renders are byte-identical when repeated.
#include "Views/EndoluminalRenderer.h"

#include "Core/Error.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <cmath>
#include <vector>

using namespace colonmap;
using namespace colonmap::views;

namespace {

constexpr double kTube = 12.0;  // mm
const Eigen::Vector3d kBump(kTube, 0, 40);  // on the +x wall

short Hu(const Eigen::Vector3d& p) {
  const bool air = std::hypot(p(0), p(1)) < kTube && (p - kBump).norm() > 5.0;
  return air ? -1000 : 40;
}

// A 64 mm cube (1 mm voxels) centred on the tube axis, stored with the given direction matrix.
Volume<short> Phantom(const Eigen::Matrix3d& direction) {
  Volume<short> v;
  v.size = {64, 64, 64};
  v.spacing = Eigen::Vector3d(1, 1, 1);
  v.direction = direction;
  // Choose the origin so that the index box covers [-32, 31] on each physical axis.
  v.origin = -direction * Eigen::Vector3d(31.5, 31.5, 31.5) + Eigen::Vector3d(0, 0, 32);
  v.Allocate();
  for (std::size_t k = 0; k < 64; ++k)
    for (std::size_t j = 0; j < 64; ++j)
      for (std::size_t i = 0; i < 64; ++i) v.At(i, j, k) = Hu(v.IndexToPhysical(Eigen::Vector3d(i, j, k)));
  return v;
}

double Mean(const RgbImage& im, int x0, int y0, int x1, int y1) {
  double s = 0;
  int n = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x, ++n)
      for (int c = 0; c < 3; ++c) s += im.rgb[(static_cast<std::size_t>(y) * im.width + x) * 3 + c] / 3.0;
  return s / n;
}

EndoluminalRenderOptions Small() {
  EndoluminalRenderOptions o;
  o.width = o.height = 96;
  o.viewAngleDeg = 90;
  o.cropRadiusMm = 40;
  return o;
}

CameraPose Looking(const Eigen::Vector3d& from, const Eigen::Vector3d& dir, const Eigen::Vector3d& up) {
  CameraPose c;
  c.position = from;
  c.focalPoint = from + dir;
  c.viewUp = up;
  return c;
}

}  // namespace

TEST(EndoluminalRenderer, DownTheTubeAndAtTheWall) {
  EndoluminalRenderer r(Small());
  const Volume<short> ct = Phantom(Eigen::Matrix3d::Identity());
  const RgbImage down = r.Render(ct, Looking({0, 0, 10}, {0, 0, 1}, {0, 1, 0}), "tube");
  ASSERT_EQ(down.width, 96);
  ASSERT_EQ(down.rgb.size(), 96u * 96 * 3);
  const double centre = Mean(down, 44, 44, 52, 52), rim = Mean(down, 0, 0, 96, 8);
  EXPECT_LT(centre, 10) << "the open tube ahead is dark";
  EXPECT_GT(rim, centre + 15) << "the near wall at the rim is lit";
  const RgbImage wall = r.Render(ct, Looking({0, 0, 20}, {0, 1, 0}, {0, 0, 1}), "tube");
  EXPECT_GT(Mean(wall, 40, 40, 56, 56), 60) << "the wall straight ahead is lit";
  const RgbImage again = r.Render(ct, Looking({0, 0, 10}, {0, 0, 1}, {0, 1, 0}), "tube");
  EXPECT_TRUE(again.rgb == down.rgb) << "repeated render differs";
}

TEST(EndoluminalRenderer, BumpOnItsSideWhateverTheStorageAxes) {
  EndoluminalRenderer r(Small());
  // Camera on the axis looking +z with up +y: right = forward x up = z x y = -x, so the bump on
  // the +x wall appears in the left half.
  const CameraPose cam = Looking({0, 0, 22}, {0, 0, 1}, {0, 1, 0});
  Eigen::Matrix3d flipped = Eigen::Matrix3d::Identity(), leftHanded = Eigen::Matrix3d::Identity();
  flipped(0, 0) = flipped(1, 1) = -1;  // still right-handed
  leftHanded(0, 0) = -1;               // determinant -1
  RgbImage ref;
  const std::vector<Eigen::Matrix3d> directions{Eigen::Matrix3d::Identity(), flipped, leftHanded};
  for (const Eigen::Matrix3d& d : directions) {
    const RgbImage im = r.Render(Phantom(d), cam, "tube");
    const double left = Mean(im, 8, 30, 40, 66), right = Mean(im, 56, 30, 88, 66);
    EXPECT_GT(left, right + 10) << "the bump is on the left (direction det " << d.determinant() << ")";
    if (ref.rgb.empty()) {
      ref = im;
      continue;
    }
    double diff = 0;
    for (std::size_t i = 0; i < im.rgb.size(); ++i) diff += std::abs(int(im.rgb[i]) - int(ref.rgb[i]));
    EXPECT_LT(diff / im.rgb.size(), 3.0) << "same physical CT, other storage axes: the picture changed";
  }
}

TEST(EndoluminalRenderer, CameraOutsideTheImageAndBadOptions) {
  EndoluminalRenderer r(Small());
  EXPECT_THROW(r.Render(Phantom(Eigen::Matrix3d::Identity()), Looking({0, 0, 200}, {0, 0, 1}, {0, 1, 0}), "tube"), Error);
  EndoluminalRenderOptions bad = Small();
  bad.preset = "nonsense";
  EXPECT_THROW(EndoluminalRenderer{bad}, Error);
  bad = Small();
  bad.viewAngleDeg = 200;
  EXPECT_THROW(EndoluminalRenderer{bad}, Error);
}
