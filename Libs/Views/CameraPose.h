#pragma once
// A camera pose (VTK/Slicer camera: position, focal point, view-up; LPS mm) and the two pieces
// of pure camera geometry the linked endoluminal views need (DESIGN §2.5): the frame built from a
// camera point c, a view-axis wall point q0 and an up-axis wall point q1, and the pinhole
// projection of a 3D point into a rendered view (to draw findings as markers). Eigen only.
#include <Eigen/Core>

namespace colonmap::views {

struct CameraPose {
  Eigen::Vector3d position{0, 0, 0};
  Eigen::Vector3d focalPoint{0, 0, 1};
  Eigen::Vector3d viewUp{0, 1, 0};
};

// The orthonormal frame of DESIGN §2.5: e3 = (q0 - c)/|q0 - c| (view axis),
// e1 = (q1 - c) x e3 normalised, e2 = e3 x e1 (the up axis: the part of q1 - c normal to e3).
struct CameraFrame {
  Eigen::Vector3d e1, e2, e3;
};

// Throws colonmap::Error when q0 == c or q1 - c is parallel to the view axis (no frame).
CameraFrame FrameFromPoints(const Eigen::Vector3d& c, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

// The camera at c looking at q0 with view-up e2 (so the up axis hits q1's side).
CameraPose CameraFromPoints(const Eigen::Vector3d& c, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1);

// Angle (degrees) between the camera's view axis and the direction from the camera to p.
double AngleToViewAxisDeg(const CameraPose& camera, const Eigen::Vector3d& p);

// Pixel (x right, y down, origin at the top-left corner of the top-left pixel) where p appears in
// a width x height perspective view of `camera` with vertical view angle `viewAngleDeg` (as
// vtkCamera with the default vertical view angle). False when p is behind the camera.
bool ProjectToPixel(const CameraPose& camera, double viewAngleDeg, int width, int height, const Eigen::Vector3d& p,
                    Eigen::Vector2d* pixel);

// The pose rotated by `angleDeg` about its own view-up axis through its position (a deliberately
// wrong camera for tests, or a user's look-around).
CameraPose YawCamera(const CameraPose& camera, double angleDeg);

}  // namespace colonmap::views
