// Camera mapping of the linked endoluminal views (DESIGN §2.5) on synthetic cylinders with known
// maps: the frame on hand-computed points; an identity registration gives back the same camera;
// a rigid motion gives the moved camera; a bent colon (the straight cylinder wrapped onto an
// arc, with a known centreline) gives the camera on the bent centreline looking at the bent
// wall point; a finding is looked at from the given distance along the skeleton.
#include "Views/CameraJson.h"
#include "Views/CameraLink.h"
#include "Views/CameraPose.h"
#include "Views/CameraWall.h"
#include "Views/SkeletonCorrespondence.h"

#include "Core/Error.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>

using namespace colonmap;
using namespace colonmap::views;

namespace {

constexpr double kRadius = 20.0, kLength = 200.0;
constexpr int kAround = 48, kAlong = 100;

// A cylinder along z (axis x = y = 0), cut along theta = 0 (seam vertices duplicated, as a
// flattened segment is), with SupineFlatUV (u = theta / 2pi, v = z / circumference) and
// PronePosition = map(V).
TriangleMesh Cylinder(const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& map) {
  TriangleMesh m;
  const int n = (kAround + 1) * (kAlong + 1);
  m.V.resize(n, 3);
  Eigen::MatrixXd uv(n, 2), image(n, 3);
  for (int j = 0; j <= kAlong; ++j)
    for (int i = 0; i <= kAround; ++i) {
      const int k = j * (kAround + 1) + i;
      const double a = 2 * M_PI * (i == kAround ? 0 : double(i) / kAround), z = kLength * j / kAlong;
      m.V.row(k) << kRadius * std::cos(a), kRadius * std::sin(a), z;
      uv.row(k) << double(i) / kAround, z / (2 * M_PI * kRadius);
      image.row(k) = map(m.V.row(k).transpose()).transpose();
    }
  m.F.resize(2 * kAround * kAlong, 3);
  int f = 0;
  for (int j = 0; j < kAlong; ++j)
    for (int i = 0; i < kAround; ++i) {
      const int a = j * (kAround + 1) + i, b = a + 1, c = a + kAround + 1, d = c + 1;
      m.F.row(f++) << a, b, d;
      m.F.row(f++) << a, d, c;
    }
  m.pointData["SupineFlatUV"] = DataArray{uv, false};
  m.pointData["PronePosition"] = DataArray{image, false};
  m.pointData["SegmentId"] = DataArray{Eigen::MatrixXd::Zero(n, 1), true};
  return m;
}

Eigen::Vector3d Identity(const Eigen::Vector3d& p) { return p; }

struct Rigid {
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
  Eigen::Vector3d operator()(const Eigen::Vector3d& p) const { return R * p + t; }
};

Rigid SomeRigid() {
  Rigid r;
  r.R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()).toRotationMatrix();
  r.t = Eigen::Vector3d(12, -40, 7);
  return r;
}

// The cylinder's axis wrapped onto an arc of radius kBend in the x-z plane: centreline
// C(z) = (kBend (1 - cos phi), 0, kBend sin phi), phi = z / kBend, with x carried along the arc's
// normal N and y kept: a smooth known bending whose loops' mass centres lie exactly on C.
constexpr double kBend = 150.0;
Eigen::Vector3d BendCentre(double z) {
  const double phi = z / kBend;
  return Eigen::Vector3d(kBend * (1 - std::cos(phi)), 0, kBend * std::sin(phi));
}
Eigen::Vector3d Bend(const Eigen::Vector3d& p) {
  const double phi = p(2) / kBend;
  const Eigen::Vector3d N(std::cos(phi), 0, -std::sin(phi));
  return BendCentre(p(2)) + p(0) * N + p(1) * Eigen::Vector3d::UnitY();
}

void ExpectNear(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double tol, const char* what) {
  EXPECT_LT((a - b).norm(), tol) << what << ": " << a.transpose() << " vs " << b.transpose();
}

double AngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), a.dot(b)) * 180 / M_PI;
}

CameraPose Camera(const Eigen::Vector3d& pos, const Eigen::Vector3d& dir, const Eigen::Vector3d& up) {
  CameraPose c;
  c.position = pos;
  c.focalPoint = pos + dir;
  c.viewUp = up;
  return c;
}

}  // namespace

TEST(CameraFrame, KnownAnswer) {
  const CameraFrame f = FrameFromPoints({0, 0, 0}, {0, 0, 5}, {0, 3, 1});
  ExpectNear(f.e3, {0, 0, 1}, 1e-12, "e3");
  ExpectNear(f.e1, {1, 0, 0}, 1e-12, "e1");  // (q1 - c) x e3 = (3, 0, 0)
  ExpectNear(f.e2, {0, 1, 0}, 1e-12, "e2");
  const CameraPose p = CameraFromPoints({1, 1, 1}, {1, 1, 6}, {1, 4, 2});
  ExpectNear(p.viewUp, {0, 1, 0}, 1e-12, "viewUp");
  ExpectNear(p.focalPoint, {1, 1, 6}, 1e-12, "focal");
  EXPECT_THROW(FrameFromPoints({0, 0, 0}, {0, 0, 0}, {0, 1, 0}), Error);
  EXPECT_THROW(FrameFromPoints({0, 0, 0}, {0, 0, 2}, {0, 0, 7}), Error);
}

TEST(CameraPose, ProjectionAndAngle) {
  const CameraPose c = Camera({0, 0, 0}, {0, 0, 10}, {0, 1, 0});
  Eigen::Vector2d px;
  ASSERT_TRUE(ProjectToPixel(c, 90, 200, 100, {0, 0, 30}, &px));
  EXPECT_NEAR(px(0), 100, 1e-9);
  EXPECT_NEAR(px(1), 50, 1e-9);
  // 45 degrees up at a 90-degree vertical view angle: the top edge.
  ASSERT_TRUE(ProjectToPixel(c, 90, 200, 100, {0, 10, 10}, &px));
  EXPECT_NEAR(px(1), 0, 1e-9);
  EXPECT_NEAR(px(0), 100, 1e-9);
  // Right of the view is forward x up = z x y = -x.
  ASSERT_TRUE(ProjectToPixel(c, 90, 200, 100, {-5, 0, 10}, &px));
  EXPECT_NEAR(px(0), 100 + 25, 1e-9);
  EXPECT_FALSE(ProjectToPixel(c, 90, 200, 100, {0, 0, -1}, &px));
  EXPECT_NEAR(AngleToViewAxisDeg(c, {0, 1, 1}), 45, 1e-9);
  const CameraPose yawed = YawCamera(c, 20);
  EXPECT_NEAR(AngleToViewAxisDeg(yawed, {0, 0, 1}), 20, 1e-9);
  ExpectNear(yawed.viewUp, c.viewUp, 1e-12, "yaw keeps up");
}

TEST(CameraWall, RayAndNearest) {
  const TriangleMesh m = Cylinder(Identity);
  const CameraWall wall(m.V, m.F);
  const WallHit h = wall.Cast({0, 0, 100}, {1, 0, 0});
  ASSERT_TRUE(h.hit);
  // The inscribed polygon: between r cos(pi / n) and r.
  EXPECT_GE(h.distance, kRadius * std::cos(M_PI / kAround) - 1e-9);
  EXPECT_LE(h.distance, kRadius + 1e-9);
  ExpectNear(h.point, InterpolateAtHit(m.V, m.F, h), 1e-9, "hit point = barycentric combination");
  EXPECT_FALSE(wall.Cast({0, 0, 100}, {0, 0, 1}).hit);  // out through the open end
  const WallHit n = wall.Nearest({0, 15, 50});
  EXPECT_NEAR(n.distance, 5, 0.2);
  EXPECT_NEAR(n.point(2), 50, 1e-9);
}

TEST(CameraSkeleton, StraightCylinderRowsOnTheAxis) {
  const LinkedSkeleton s(Cylinder(Identity), "cylinder");
  ASSERT_GE(s.Rows().size(), 20u);
  double prevZ = -1;
  for (const SkeletonRow& r : s.Rows()) {
    EXPECT_LT(r.supine.head<2>().norm(), 1e-6);  // mass centre of a loop: on the axis
    EXPECT_GT(r.supine(2), prevZ);                // ordered from the anal end (v = 0)
    prevZ = r.supine(2);
    ExpectNear(r.prone, r.supine, 1e-9, "identity image");
  }
  EXPECT_NEAR(s.Length(), s.Rows().back().supine(2) - s.Rows().front().supine(2), 1e-9);
  const SkeletonLocation l = s.Project({3, 4, 77});
  EXPECT_NEAR(l.distance, 5, 1e-6);
  ExpectNear(s.Supine(l), {0, 0, 77}, 1e-6, "projection");
  ExpectNear(s.Supine(s.AtArc(l.arc - 25)), {0, 0, 52}, 1e-6, "25 mm before");
}

TEST(CameraSkeleton, MissingArraysAreNamed) {
  TriangleMesh m = Cylinder(Identity);
  m.pointData.erase("PronePosition");
  try {
    LinkedSkeleton s(m, "registration 'x.vtp'");
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("PronePosition"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("x.vtp"), std::string::npos) << e.what();
  }
}

TEST(CameraLink, IdentityRegistrationGivesTheSameCamera) {
  const CameraLinker link(Cylinder(Identity), "cylinder");
  for (const CameraPose& c : {Camera({0, 0, 60}, {1, 0, 1}, {0, 1, 0}), Camera({4, -3, 120}, {-1, 2, -0.5}, {1, 0.5, 0.2})}) {
    const LinkedView v = link.LinkCamera(c);
    ExpectNear(v.prone.position, v.supine.position, 1e-9, "position");
    ExpectNear(v.prone.focalPoint, v.supine.focalPoint, 1e-9, "focal");
    ExpectNear(v.prone.viewUp, v.supine.viewUp, 1e-9, "up");
    ExpectNear(v.supine.position, c.position, 1e-12, "supine position kept");
    EXPECT_LT(AngleDeg(v.supine.focalPoint - c.position, c.focalPoint - c.position), 1e-9);
  }
}

TEST(CameraLink, RigidMotionGivesTheMovedCamera) {
  const Rigid rigid = SomeRigid();
  const CameraLinker link(Cylinder(rigid), "cylinder");
  for (const CameraPose& c : {Camera({0, 0, 60}, {1, 0, 1}, {0, 1, 0}), Camera({4, -3, 120}, {-1, 2, -0.5}, {1, 0.5, 0.2})}) {
    const LinkedView v = link.LinkCamera(c);
    ExpectNear(v.prone.position, rigid(c.position), 1e-6, "position");
    ExpectNear(v.prone.focalPoint, rigid(v.supine.focalPoint), 1e-6, "focal");
    ExpectNear(v.prone.viewUp, rigid.R * v.supine.viewUp, 1e-6, "up");
  }
}

TEST(CameraLink, BentColonGivesTheCameraOnTheBentCentreline) {
  const CameraLinker link(Cylinder(Bend), "bent cylinder");
  // Rows' prone mass centres lie on the bent centreline.
  for (const SkeletonRow& r : link.Skeleton().Rows()) ExpectNear(r.prone, BendCentre(r.supine(2)), 0.05, "row centre");
  for (double z : {40.0, 100.0, 151.0}) {
    const CameraPose c = Camera({0, 0, z}, {1, 0.5, 0.8}, {0, 1, 0});
    const LinkedView v = link.LinkCamera(c);
    ExpectNear(v.prone.position, BendCentre(z), 0.1, "camera on the bent centreline");
    // View axis towards the bent image of p0, up towards the bent image of p1.
    EXPECT_LT(AngleDeg(v.prone.focalPoint - v.prone.position, Bend(v.p0) - BendCentre(z)), 0.2);
    const Eigen::Vector3d e3 = (Bend(v.p0) - BendCentre(z)).normalized();
    const Eigen::Vector3d up = Bend(v.p1) - BendCentre(z);
    EXPECT_LT(AngleDeg(v.prone.viewUp, up - up.dot(e3) * e3), 0.2);
  }
  // Off the skeleton: the offset turns with the loop (x goes along the arc's normal).
  const double z = 90;
  const LinkedView off = link.LinkCamera(Camera({5, 0, z}, {0, 1, 1}, {-1, 0, 0}));
  ExpectNear(off.prone.position, Bend({5, 0, z}), 0.2, "off-skeleton camera");
}

TEST(CameraLink, FindingIsLookedAtFromTheGivenDistance) {
  const Rigid rigid = SomeRigid();
  for (int moved = 0; moved < 2; ++moved) {
    const CameraLinker link = moved ? CameraLinker(Cylinder(rigid), "cylinder") : CameraLinker(Cylinder(Identity), "cylinder");
    const double a = 1.1;
    const Eigen::Vector3d finding((kRadius - 3) * std::cos(a), (kRadius - 3) * std::sin(a), 101);
    const LinkedView v = link.LinkFinding(finding, 25);
    ASSERT_TRUE(v.hasFinding);
    ExpectNear(v.supine.position, {0, 0, 76}, 1e-6, "camera 25 mm before, on the axis");
    EXPECT_LT(AngleToViewAxisDeg(v.supine, finding), 1e-9);  // the finding is on the view axis
    EXPECT_NEAR(std::abs(v.findingHeight), 3, 0.3);
    const Eigen::Vector3d truth = moved ? rigid(finding) : finding;
    ExpectNear(v.proneFinding, truth, 1e-6, "mapped finding");
    EXPECT_LT(v.proneAngleDeg, 1e-6);
    EXPECT_LT(AngleToViewAxisDeg(v.prone, truth), 1e-6);
    // The up axis is the anterior direction (-y) made normal to the view axis.
    const Eigen::Vector3d d = (finding - v.supine.position).normalized();
    const Eigen::Vector3d ant = Eigen::Vector3d(0, -1, 0) - Eigen::Vector3d(0, -1, 0).dot(d) * d;
    EXPECT_LT(AngleDeg(v.supine.viewUp, ant), 1e-6);
  }
}

TEST(CameraLink, AxisLeavingThroughAnOpenEndIsAnError) {
  const CameraLinker link(Cylinder(Identity), "cylinder");
  EXPECT_THROW(link.LinkCamera(Camera({0, 0, 100}, {0, 0, 1}, {0, 1, 0})), Error);
}

TEST(CameraJson, RoundTripOfOwnOutput) {
  const CameraLinker link(Cylinder(SomeRigid()), "cylinder");
  ViewRecord r;
  r.label = "P 1";
  r.image = "view_P_1.png";
  r.view = link.LinkCamera(Camera({0, 0, 60}, {1, 0, 1}, {0, 1, 0}));
  const std::string text = CamerasJsonText({r}, 100, 512, 512);
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "colonmap-camera-json-test.json";
  std::ofstream(path) << text;
  const std::vector<NamedCamera> back = ReadCameras(path.string(), "cameras");
  std::filesystem::remove(path);
  ASSERT_EQ(back.size(), 1u);
  EXPECT_EQ(back[0].label, "P 1");
  ExpectNear(back[0].pose.position, r.view.supine.position, 1e-9, "position");
  ExpectNear(back[0].pose.focalPoint, r.view.supine.focalPoint, 1e-9, "focal");
  EXPECT_EQ(SafeLabel("P 1/a", "V1"), "P_1_a");
  EXPECT_EQ(SafeLabel("", "V1"), "V1");
  EXPECT_THROW(ReadCameras("/nonexistent/cameras.json", "cameras"), Error);
}

// Found by fuzzing (issue 24): a camera looking nowhere, or with its view-up along the view
// direction, was accepted and gave VTK a degenerate view matrix.
TEST(CameraJson, DegenerateCamerasRefused) {
  const std::filesystem::path path = std::filesystem::temp_directory_path() / "colonmap-camera-json-degenerate.json";
  const auto errorOf = [&](const std::string& text) {
    std::ofstream(path) << text;
    try {
      ReadCameras(path.string(), "cameras");
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(errorOf(R"({"views":[{"position":[0,0,0],"focalPoint":[0,0,0],"viewUp":[0,0,1]}]})"),
            "cameras '" + path.string() + "': view 1: 'focalPoint' equals 'position'");
  EXPECT_EQ(errorOf(R"([{"position":[0,0,0],"focalPoint":[0,1,0],"viewUp":[0,0,1]},
                        {"position":[0,0,0],"focalPoint":[0,0,1],"viewUp":[0,0,2]}])"),
            "cameras '" + path.string() + "': view 2: 'viewUp' is zero or along the view direction");
  EXPECT_NE(errorOf(R"([{"position":[0,0,0],"focalPoint":[0,1,0],"viewUp":[0,0,0]}])").find("'viewUp' is zero"), std::string::npos);
  EXPECT_EQ(errorOf(R"([{"position":[0,0,0],"focalPoint":[0,1,0],"viewUp":[0,0,1]}])"), "");
  std::filesystem::remove(path);
}
