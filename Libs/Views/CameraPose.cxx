#include "Views/CameraPose.h"

#include "Core/Error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace colonmap::views {

CameraFrame FrameFromPoints(const Eigen::Vector3d& c, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const Eigen::Vector3d axis = q0 - c;
  if (!(axis.norm() > 1e-9)) throw Error("camera frame: the view-axis point coincides with the camera point");
  CameraFrame f;
  f.e3 = axis.normalized();
  const Eigen::Vector3d side = (q1 - c).cross(f.e3);
  // Relative test: q1 - c must not be (nearly) along the view axis.
  if (!(side.norm() > 1e-6 * std::max(1.0, (q1 - c).norm())))
    throw Error("camera frame: the up-axis point lies on the view axis");
  f.e1 = side.normalized();
  f.e2 = f.e3.cross(f.e1);
  return f;
}

CameraPose CameraFromPoints(const Eigen::Vector3d& c, const Eigen::Vector3d& q0, const Eigen::Vector3d& q1) {
  const CameraFrame f = FrameFromPoints(c, q0, q1);
  CameraPose p;
  p.position = c;
  p.focalPoint = q0;
  p.viewUp = f.e2;
  return p;
}

double AngleToViewAxisDeg(const CameraPose& camera, const Eigen::Vector3d& p) {
  const Eigen::Vector3d a = (camera.focalPoint - camera.position).normalized();
  const Eigen::Vector3d d = (p - camera.position).normalized();
  // atan2 of |cross| and dot: accurate for small angles, where acos is not.
  return std::atan2(a.cross(d).norm(), a.dot(d)) * 180.0 / M_PI;
}

bool ProjectToPixel(const CameraPose& camera, double viewAngleDeg, int width, int height, const Eigen::Vector3d& p,
                    Eigen::Vector2d* pixel) {
  const Eigen::Vector3d forward = (camera.focalPoint - camera.position).normalized();
  const Eigen::Vector3d up = (camera.viewUp - camera.viewUp.dot(forward) * forward).normalized();
  const Eigen::Vector3d right = forward.cross(up);
  const Eigen::Vector3d d = p - camera.position;
  const double z = d.dot(forward);
  if (!(z > 1e-9)) return false;
  const double f = 0.5 * height / std::tan(0.5 * viewAngleDeg * M_PI / 180.0);
  (*pixel)(0) = 0.5 * width + f * d.dot(right) / z;
  (*pixel)(1) = 0.5 * height - f * d.dot(up) / z;
  return true;
}

CameraPose YawCamera(const CameraPose& camera, double angleDeg) {
  const Eigen::Vector3d forward = camera.focalPoint - camera.position;
  const Eigen::Vector3d up = (camera.viewUp - camera.viewUp.dot(forward.normalized()) * forward.normalized()).normalized();
  const Eigen::AngleAxisd r(angleDeg * M_PI / 180.0, up);
  CameraPose out = camera;
  out.focalPoint = camera.position + r * forward;
  out.viewUp = r * camera.viewUp;
  return out;
}

}  // namespace colonmap::views
