#pragma once
// Linked endoluminal cameras (DESIGN §2.5): a supine camera at skeleton point o looking at wall
// point p0 (the view axis hits the wall there) with its up axis hitting wall point p1 becomes the
// prone camera at c (the prone skeleton point matching o through the flattened centerlines,
// SkeletonCorrespondence.h) looking at q0 with up towards q1, where q0, q1 are the images of
// p0, p1 under the registration (barycentric combination of PronePosition over the hit
// triangle). Frame: e3 = (q0 - c)/|q0 - c|, e1 = (q1 - c) x e3 normalised, e2 = e3 x e1.
// Everything comes from registration.vtp alone (supine mesh + per-vertex prone images). Eigen only.
#include "Core/TriangleMesh.h"
#include "Views/CameraPose.h"
#include "Views/CameraWall.h"
#include "Views/SkeletonCorrespondence.h"

#include <Eigen/Core>

#include <string>

namespace colonmap::views {

struct LinkedView {
  CameraPose supine, prone;       // supine focalPoint = p0, prone focalPoint = q0; viewUp = e2
  Eigen::Vector3d p0{0, 0, 0}, p1{0, 0, 0}, q0{0, 0, 0}, q1{0, 0, 0};
  double skeletonArc = 0;         // supine arc length of o's skeleton point from the anal end (mm)
  double skeletonOffset = 0;      // distance of o from the supine skeleton (mm)
  // Findings only (LinkFinding):
  bool hasFinding = false;
  Eigen::Vector3d finding{0, 0, 0};       // supine, as given
  Eigen::Vector3d proneFinding{0, 0, 0};  // mapped: wall foot's image + the same height above the wall
  double findingHeight = 0;               // signed distance of the finding from the supine wall (mm)
  double proneAngleDeg = 0;               // angle between the prone view axis and c -> proneFinding
};

class CameraLinker {
 public:
  // registration: registration.vtp as read (supine V, F; point arrays SupineFlatUV, PronePosition,
  // SegmentId). Throws colonmap::Error naming `what` when arrays are missing.
  CameraLinker(const TriangleMesh& registration, const std::string& what, const SkeletonOptions& options = {});

  // A supine camera (position o, its view axis and up axis cast onto the wall) and its prone twin.
  // Throws colonmap::Error when an axis does not hit the wall (e.g. it leaves through an open end).
  LinkedView LinkCamera(const CameraPose& supine) const;

  // A camera on the supine skeleton `distanceMm` before the finding's nearest skeleton point
  // (towards the anal end; negative: towards the cecum), looking through the finding at the wall
  // behind it (p0), up axis = `upHint` made normal to the view axis (default anterior, -y in LPS;
  // superior when the view is anterior), then linked as LinkCamera.
  LinkedView LinkFinding(const Eigen::Vector3d& finding, double distanceMm,
                         const Eigen::Vector3d& upHint = Eigen::Vector3d(0, -1, 0)) const;

  // The prone image of a supine point near the wall: its wall foot mapped, plus its signed height
  // above the supine wall re-applied along the image triangle's normal.
  Eigen::Vector3d MapNearWallPoint(const Eigen::Vector3d& p, double* height = nullptr) const;

  const LinkedSkeleton& Skeleton() const { return skeleton_; }
  const CameraWall& Wall() const { return wall_; }

 private:
  LinkedView Link(const Eigen::Vector3d& o, const WallHit& h0, const WallHit& h1) const;
  CameraWall wall_;
  Eigen::MatrixXd image_;  // PronePosition, n x 3
  LinkedSkeleton skeleton_;
};

}  // namespace colonmap::views
