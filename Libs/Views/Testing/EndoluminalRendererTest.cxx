// The endoluminal renderer (VTK ray casting, under xvfb-run) on a synthetic CT: an air tube in
// soft tissue with a tissue bump on one side. Looking down the tube the centre is dark (far,
// open) and the rim bright (near wall); looking at the wall the centre is bright; the bump shows
// on the side it is on, also when the same physical CT is stored with flipped or left-handed
// axes (direction cosines honoured); renders are byte-identical when repeated; a Cancel heard
// while a picture renders stops it part way.
#include "Views/EndoluminalRenderer.h"
#include "Core/RecordingProgress.h"

#include "Core/Cancel.h"
#include "Core/Error.h"

#include <gtest/gtest.h>

#include <Eigen/LU>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <iostream>
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

// A 64 mm cube (voxels of `spacing` mm) centred on the tube axis, stored with the given direction
// matrix; with `noise`, up to that many HU of fixed pseudo-random noise, as a CT has (every voxel
// then has a gradient direction for VTK to encode).
Volume<short> Phantom(const Eigen::Matrix3d& direction, double spacing = 1.0, int noise = 0) {
  const std::size_t n = static_cast<std::size_t>(std::lround(64 / spacing));
  Volume<short> v;
  v.size = {n, n, n};
  v.spacing = Eigen::Vector3d::Constant(spacing);
  v.direction = direction;
  // Choose the origin so that the index box covers [-32, 32) on each physical axis.
  v.origin = -direction * Eigen::Vector3d::Constant(0.5 * (n - 1) * spacing) + Eigen::Vector3d(0, 0, 32);
  v.Allocate();
  for (std::size_t k = 0; k < n; ++k)
    for (std::size_t j = 0; j < n; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const std::size_t hash = (i * 73856093u) ^ (j * 19349663u) ^ (k * 83492791u);
        const int jitter = noise ? static_cast<int>(hash % (2 * noise + 1)) - noise : 0;
        v.At(i, j, k) = static_cast<short>(Hu(v.IndexToPhysical(Eigen::Vector3d(i, j, k))) + jitter);
      }
  return v;
}

double SecondsOf(const std::function<void()>& f) {
  const auto start = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
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

// VTK computes the gradients of the whole crop before it casts a ray, with no abort check of its
// own: the picture's progress is heard from inside that pass, and a Cancel there skips the rest
// of the picture, which is thrown away; the renderer's next picture is whole.
TEST(EndoluminalRenderer, HearsCancelWhileRenderingAndThenRendersWhole) {
  EndoluminalRenderOptions o = Small();
  o.width = o.height = 256;
  const Volume<short> ct = Phantom(Eigen::Matrix3d::Identity(), 0.4, 20);  // 160^3 voxels
  const CameraPose cam = Looking({0, 0, 10}, {0, 0, 1}, {0, 1, 0});
  EndoluminalRenderer r(o);
  const RgbImage ref = r.Render(ct, cam, "tube");
  RecordingProgress whole;
  RgbImage same;
  const double wholeSeconds = SecondsOf([&] { same = r.Render(ct, cam, "tube", &whole); });
  EXPECT_TRUE(same.rgb == ref.rgb) << "listening changed the picture";
  ASSERT_GE(whole.fractions.size(), 4u) << "progress from inside the picture";
  EXPECT_TRUE(std::is_sorted(whole.fractions.begin(), whole.fractions.end()));
  EXPECT_GE(whole.fractions.front(), 0.0);
  EXPECT_LE(whole.fractions.back(), 1.0);

  RecordingProgress cancelling(1);
  const double cancelledSeconds = SecondsOf([&] { EXPECT_THROW(r.Render(ct, cam, "tube", &cancelling), Cancelled); });
  EXPECT_EQ(cancelling.fractions.size(), 1u) << "heard more after the Cancel";
  EXPECT_LT(cancelledSeconds, 0.5 * wholeSeconds) << "the rest of the picture was not skipped (whole picture "
                                                  << wholeSeconds << " s, cancelled " << cancelledSeconds << " s)";
  std::cout << "whole picture " << wholeSeconds << " s (" << whole.fractions.size() << " reports), cancelled at the first "
            << cancelledSeconds << " s\n";
  const RgbImage after = r.Render(ct, cam, "tube");
  EXPECT_TRUE(after.rgb == ref.rgb) << "the picture after a Cancel is not whole";
}
