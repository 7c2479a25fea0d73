#include "Views/CameraLink.h"

#include "Core/Error.h"

#include <Eigen/Geometry>

#include <cmath>

namespace colonmap::views {

namespace {

const Eigen::MatrixXd& ProneImages(const TriangleMesh& mesh, const std::string& what) {
  const auto it = mesh.pointData.find("PronePosition");
  if (it == mesh.pointData.end() || it->second.values.rows() != mesh.V.rows() || it->second.values.cols() != 3)
    throw Error(what + ": no point array PronePosition (3 components per vertex)");
  return it->second.values;
}

Eigen::Vector3d ImageNormal(const Eigen::MatrixXd& image, const Eigen::MatrixXi& F, int f) {
  const Eigen::Vector3d a = image.row(F(f, 0)), b = image.row(F(f, 1)), c = image.row(F(f, 2));
  return (b - a).cross(c - a).normalized();
}

std::string Mm(const Eigen::Vector3d& p) {
  char b[96];
  std::snprintf(b, sizeof b, "(%.1f, %.1f, %.1f)", p(0), p(1), p(2));
  return b;
}

}  // namespace

CameraLinker::CameraLinker(const TriangleMesh& registration, const std::string& what, const SkeletonOptions& options)
    : wall_(registration.V, registration.F), image_(ProneImages(registration, what)),
      skeleton_(registration, what, options) {}

LinkedView CameraLinker::Link(const Eigen::Vector3d& o, const WallHit& h0, const WallHit& h1) const {
  LinkedView view;
  view.p0 = h0.point;
  view.p1 = h1.point;
  view.q0 = InterpolateAtHit(image_, wall_.F(), h0);
  view.q1 = InterpolateAtHit(image_, wall_.F(), h1);
  const SkeletonLocation l = skeleton_.Project(o);
  view.skeletonArc = l.arc;
  view.skeletonOffset = l.distance;
  const Eigen::Vector3d c = skeleton_.Prone(l) + skeleton_.Rotation(l) * (o - skeleton_.Supine(l));
  view.supine = CameraFromPoints(o, view.p0, view.p1);
  view.prone = CameraFromPoints(c, view.q0, view.q1);
  return view;
}

LinkedView CameraLinker::LinkCamera(const CameraPose& supine) const {
  const Eigen::Vector3d o = supine.position;
  const Eigen::Vector3d axis = supine.focalPoint - o;
  if (!(axis.norm() > 1e-9)) throw Error("camera at " + Mm(o) + ": focal point equals position");
  const Eigen::Vector3d d = axis.normalized();
  const Eigen::Vector3d up = supine.viewUp - supine.viewUp.dot(d) * d;
  if (!(up.norm() > 1e-9)) throw Error("camera at " + Mm(o) + ": view-up is parallel to the view axis");
  const WallHit h0 = wall_.Cast(o, d), h1 = wall_.Cast(o, up.normalized());
  if (!h0.hit) throw Error("camera at " + Mm(o) + ": the view axis does not hit the colon wall");
  if (!h1.hit) throw Error("camera at " + Mm(o) + ": the up axis does not hit the colon wall");
  return Link(o, h0, h1);
}

LinkedView CameraLinker::LinkFinding(const Eigen::Vector3d& finding, double distanceMm, const Eigen::Vector3d& upHint) const {
  const SkeletonLocation at = skeleton_.Project(finding);
  const Eigen::Vector3d o = skeleton_.Supine(skeleton_.AtArc(at.arc - distanceMm));
  const Eigen::Vector3d axis = finding - o;
  if (!(axis.norm() > 0.5)) throw Error("finding at " + Mm(finding) + ": too close to the skeleton to look at");
  const Eigen::Vector3d d = axis.normalized();
  // The wall behind the finding along the view axis (the finding lies on the axis); a finding
  // outside the wall mesh (e.g. just beyond it) falls back to its nearest wall point.
  WallHit h0 = wall_.Cast(o, d);
  if (!h0.hit) h0 = wall_.Nearest(finding);
  Eigen::Vector3d up = upHint - upHint.dot(d) * d;
  if (up.norm() < 0.3 * upHint.norm()) {
    const Eigen::Vector3d superior(0, 0, 1);
    up = superior - superior.dot(d) * d;
  }
  const WallHit h1 = wall_.Cast(o, up.normalized());
  if (!h1.hit) throw Error("finding at " + Mm(finding) + ": the camera's up axis does not hit the colon wall");
  LinkedView view = Link(o, h0, h1);
  // Keep the supine focal point on the finding's line of sight: the view axis is o -> finding.
  view.hasFinding = true;
  view.finding = finding;
  view.proneFinding = MapNearWallPoint(finding, &view.findingHeight);
  view.proneAngleDeg = AngleToViewAxisDeg(view.prone, view.proneFinding);
  return view;
}

Eigen::Vector3d CameraLinker::MapNearWallPoint(const Eigen::Vector3d& p, double* height) const {
  const WallHit foot = wall_.Nearest(p);
  const double h = (p - foot.point).dot(wall_.FaceNormal(foot.face));
  if (height) *height = h;
  return InterpolateAtHit(image_, wall_.F(), foot) + h * ImageNormal(image_, wall_.F(), foot.face);
}

}  // namespace colonmap::views
