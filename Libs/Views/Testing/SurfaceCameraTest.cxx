// The overview camera of the 3D pictures (SurfaceCamera.h): framing from the points' extent along
// the named anatomical directions, the aspect and margin rules, the projection, and (MorphFraming)
// that one camera framing both morph ends frames every intermediate frame.
#include "Views/MorphSequence.h"
#include "Views/SurfaceCamera.h"

#include "Core/Error.h"

#include <gtest/gtest.h>

#include <random>

using namespace colonmap;
using namespace colonmap::views;

namespace {

// The 8 corners of the box [lo, hi].
Eigen::MatrixXd Corners(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
  Eigen::MatrixXd c(8, 3);
  for (int k = 0; k < 8; ++k) c.row(k) << (k & 1 ? hi : lo)(0), (k & 2 ? hi : lo)(1), (k & 4 ? hi : lo)(2);
  return c;
}

// Pixel extent (min x, min y, max x, max y) of the projected points.
Eigen::Vector4d Extent(const SurfaceCamera& c, int w, int h, const Eigen::MatrixXd& pts) {
  Eigen::Vector4d e(1e300, 1e300, -1e300, -1e300);
  for (Eigen::Index i = 0; i < pts.rows(); ++i) {
    const Eigen::Vector2d p = ProjectParallel(c, w, h, pts.row(i).transpose());
    e = Eigen::Vector4d(std::min(e(0), p.x()), std::min(e(1), p.y()), std::max(e(2), p.x()), std::max(e(3), p.y()));
  }
  return e;
}

}  // namespace

TEST(SurfaceCamera, AnteriorViewLooksAlongPosteriorWithSuperiorUpAndPatientRightOnTheLeft) {
  // A tall box (x 100 mm wide, z 300 mm high) off the origin.
  const Eigen::Vector3d lo(-30, 10, -100), hi(70, 50, 200);
  const SurfaceCamera c = FrameSurface(Corners(lo, hi), SurfaceViewNamed("anterior"), 0.75, 0.1);
  const Eigen::Vector3d centre = 0.5 * (lo + hi);
  EXPECT_LT((c.pose.focalPoint - centre).norm(), 1e-9);
  const Eigen::Vector3d look = (c.pose.focalPoint - c.pose.position).normalized();
  EXPECT_LT((look - Eigen::Vector3d(0, 1, 0)).norm(), 1e-12);  // camera in front (anterior = -y in LPS)
  EXPECT_LT(c.pose.position.y(), lo.y());
  EXPECT_LT((c.pose.viewUp - Eigen::Vector3d(0, 0, 1)).norm(), 1e-12);
  // Height 300 governs (300 * 0.75 = 225 > 100): half height 150 plus 10%.
  EXPECT_NEAR(c.parallelScale, 165.0, 1e-9);
  // Patient's left (+x) on the picture's right, superior (+z) at the top.
  const int w = 300, h = 400;
  EXPECT_GT(ProjectParallel(c, w, h, Eigen::Vector3d(hi.x(), centre.y(), centre.z())).x(), 0.5 * w);
  EXPECT_LT(ProjectParallel(c, w, h, Eigen::Vector3d(centre.x(), centre.y(), hi.z())).y(), 0.5 * h);
  // The box spans 1/1.1 of the height, centred; and every depth lies inside the clipping range.
  const Eigen::Vector4d e = Extent(c, w, h, Corners(lo, hi));
  EXPECT_NEAR(e(3) - e(1), h / 1.1, 1e-9);
  EXPECT_NEAR(e(1), h - e(3), 1e-9);
  EXPECT_NEAR(e(0), w - e(2), 1e-9);
  for (int k = 0; k < 8; ++k) {
    const double depth = (Corners(lo, hi).row(k).transpose() - c.pose.position).dot(look);
    EXPECT_GT(depth, c.nearClip);
    EXPECT_LT(depth, c.farClip);
  }
}

TEST(SurfaceCamera, WideExtentIsFramedByItsWidth) {
  // 400 mm wide, 100 mm high in a square picture: the width governs.
  const Eigen::Vector3d lo(0, 0, 0), hi(400, 20, 100);
  const SurfaceCamera c = FrameSurface(Corners(lo, hi), SurfaceViewNamed("anterior"), 1.0, 0.0);
  EXPECT_NEAR(c.parallelScale, 200.0, 1e-9);
  const Eigen::Vector4d e = Extent(c, 200, 200, Corners(lo, hi));
  EXPECT_NEAR(e(0), 0.0, 1e-9);
  EXPECT_NEAR(e(2), 200.0, 1e-9);
}

TEST(SurfaceCamera, EveryNamedViewFramesRandomPointsInsideThePicture) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::MatrixXd pts(500, 3);
  for (Eigen::Index i = 0; i < pts.rows(); ++i) pts.row(i) << 140 * u(rng) + 3, 95 * u(rng) - 2, 200 * u(rng) + 10;
  for (const char* name : {"anterior", "posterior", "left", "right", "superior"}) {
    const SurfaceViewDirection v = SurfaceViewNamed(name);
    const SurfaceCamera c = FrameSurface(pts, v, 360.0 / 480.0, 0.05);
    const Eigen::Vector4d e = Extent(c, 360, 480, pts);
    EXPECT_GT(e(0), 0) << name;
    EXPECT_GT(e(1), 0) << name;
    EXPECT_LT(e(2), 360) << name;
    EXPECT_LT(e(3), 480) << name;
    // Tight on one axis: 5% margin each side of the governing extent.
    EXPECT_NEAR(std::max((e(2) - e(0)) / 360, (e(3) - e(1)) / 480), 1 / 1.05, 1e-9) << name;
    EXPECT_LT(((c.pose.focalPoint - c.pose.position).normalized() - v.viewDirection).norm(), 1e-12) << name;
  }
  // Posterior mirrors anterior left-right: the patient's left is then on the picture's left.
  const SurfaceCamera a = FrameSurface(pts, SurfaceViewNamed("anterior"), 1, 0), p = FrameSurface(pts, SurfaceViewNamed("posterior"), 1, 0);
  const Eigen::Vector3d left = a.pose.focalPoint + Eigen::Vector3d(50, 0, 0);
  EXPECT_GT(ProjectParallel(a, 100, 100, left).x(), 50);
  EXPECT_LT(ProjectParallel(p, 100, 100, left).x(), 50);
}

TEST(SurfaceCamera, BadInputThrows) {
  const Eigen::MatrixXd one = Eigen::MatrixXd::Zero(1, 3);
  EXPECT_THROW(FrameSurface(Eigen::MatrixXd(0, 3), SurfaceViewNamed("anterior"), 1), Error);
  EXPECT_THROW(FrameSurface(one, SurfaceViewNamed("anterior"), 0), Error);
  EXPECT_THROW(FrameSurface(one, {"bad", {0, 0, 1}, {0, 0, 2}}, 1), Error);
  Eigen::MatrixXd nan = one;
  nan(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(FrameSurface(nan, SurfaceViewNamed("anterior"), 1), Error);
  EXPECT_THROW(SurfaceViewNamed("inferior-ish"), Error);
  // A single point still gets a usable camera (1 mm half height).
  EXPECT_GT(FrameSurface(one, SurfaceViewNamed("left"), 1).parallelScale, 0.0);
}

TEST(MorphFraming, OneCameraFramingBothEndsFramesEveryFrame) {
  std::mt19937 rng(9);
  std::normal_distribution<double> g(0, 40);
  Eigen::MatrixXd s(300, 3), p(300, 3);
  for (Eigen::Index i = 0; i < s.rows(); ++i) {
    s.row(i) << g(rng), g(rng), 2 * g(rng);
    p.row(i) = s.row(i) + Eigen::RowVector3d(30 + 0.2 * g(rng), -20, 0.3 * g(rng));
  }
  const SurfaceCamera c = FrameSurface(MorphFramingPoints(s, p), SurfaceViewNamed("anterior"), 0.75, 0.0);
  const Eigen::Vector4d all = Extent(c, 300, 400, MorphFramingPoints(s, p));
  for (double t : MorphTimes(7)) {
    const Eigen::Vector4d e = Extent(c, 300, 400, MorphFrame(s, p, t));
    EXPECT_GE(e(0), all(0) - 1e-9);
    EXPECT_GE(e(1), all(1) - 1e-9);
    EXPECT_LE(e(2), all(2) + 1e-9);
    EXPECT_LE(e(3), all(3) + 1e-9);
  }
  // The supine surface alone would not do: the prone end leaves its frame.
  const SurfaceCamera cs = FrameSurface(s, SurfaceViewNamed("anterior"), 0.75, 0.0);
  const Eigen::Vector4d e = Extent(cs, 300, 400, p);
  EXPECT_TRUE(e(0) < 0 || e(1) < 0 || e(2) > 300 || e(3) > 400);
  EXPECT_EQ(MorphFrameName(7, ".png"), "morph_007.png");
  EXPECT_THROW(MorphFramingPoints(s, p.topRows(10)), Error);
}
