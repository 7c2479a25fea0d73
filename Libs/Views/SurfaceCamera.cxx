#include "Views/SurfaceCamera.h"

#include "Core/Error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace colonmap::views {
namespace {

struct Axes {
  Eigen::Vector3d forward, right, up;
};

Axes AxesOf(const Eigen::Vector3d& direction, const Eigen::Vector3d& viewUp) {
  Axes a;
  if (!(direction.norm() > 0) || !direction.allFinite()) throw Error("surface camera: no view direction");
  a.forward = direction.normalized();
  // Up made orthogonal to the view (what vtkCamera::OrthogonalizeViewUp does).
  const Eigen::Vector3d up = viewUp - viewUp.dot(a.forward) * a.forward;
  if (!(up.norm() > 1e-9 * std::max(1.0, viewUp.norm()))) throw Error("surface camera: the view-up is parallel to the view direction");
  a.up = up.normalized();
  a.right = a.forward.cross(a.up);  // VTK: direction of projection x view-up
  return a;
}

}  // namespace

SurfaceViewDirection SurfaceViewNamed(const std::string& name) {
  if (name == "anterior") return {name, {0, 1, 0}, {0, 0, 1}};
  if (name == "posterior") return {name, {0, -1, 0}, {0, 0, 1}};
  if (name == "left") return {name, {-1, 0, 0}, {0, 0, 1}};
  if (name == "right") return {name, {1, 0, 0}, {0, 0, 1}};
  if (name == "superior") return {name, {0, 0, -1}, {0, -1, 0}};
  throw Error("3D view '" + name + "': must be anterior, posterior, left, right or superior");
}

SurfaceCamera FrameSurface(const Eigen::MatrixXd& points, const SurfaceViewDirection& view, double aspect, double margin) {
  if (points.rows() < 1 || points.cols() != 3) throw Error("surface camera: no points to frame");
  if (!points.allFinite()) throw Error("surface camera: points are not finite");
  if (!(aspect > 0) || !std::isfinite(aspect)) throw Error("surface camera: the picture aspect must be > 0");
  if (!(margin >= 0 && margin < 10)) throw Error("surface camera: the margin must be in [0, 10)");
  const Axes a = AxesOf(view.viewDirection, view.viewUp);
  Eigen::MatrixXd axes(3, 3);
  axes << a.right, a.up, a.forward;
  const Eigen::MatrixXd q = points * axes;  // n x 3: right, up, forward coordinates
  const Eigen::Vector3d lo = q.colwise().minCoeff().transpose(), hi = q.colwise().maxCoeff().transpose();
  const Eigen::Vector3d mid = 0.5 * (lo + hi);
  const double halfW = 0.5 * (hi(0) - lo(0)), halfH = 0.5 * (hi(1) - lo(1));
  // Half height that fits both extents; a single point (or a line along the view) gets 1 mm.
  const double half = std::max({halfH, halfW / aspect, 0.5});
  SurfaceCamera c;
  c.parallelScale = half * (1.0 + margin);
  const Eigen::Vector3d centre = axes * mid;
  double radius = 0;
  for (Eigen::Index i = 0; i < points.rows(); ++i) radius = std::max(radius, (points.row(i).transpose() - centre).norm());
  const double distance = 1.1 * radius + 1.0;
  c.pose.focalPoint = centre;
  c.pose.position = centre - distance * a.forward;
  c.pose.viewUp = a.up;
  // Depths of the points along the view, from the camera, with 1 mm to spare each side.
  c.nearClip = std::max(0.01, distance + (lo(2) - mid(2)) - 1.0);
  c.farClip = distance + (hi(2) - mid(2)) + 1.0;
  return c;
}

Eigen::Vector2d ProjectParallel(const SurfaceCamera& camera, int width, int height, const Eigen::Vector3d& p) {
  const Axes a = AxesOf(camera.pose.focalPoint - camera.pose.position, camera.pose.viewUp);
  const double perMm = 0.5 * height / camera.parallelScale;  // pixels per mm
  const Eigen::Vector3d d = p - camera.pose.focalPoint;
  return {0.5 * width + perMm * d.dot(a.right), 0.5 * height - perMm * d.dot(a.up)};
}

}  // namespace colonmap::views
