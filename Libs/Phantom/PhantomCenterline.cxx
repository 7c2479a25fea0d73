#include "PhantomCenterline.h"

#include "ColonAnatomy.h"

namespace colonmap {
namespace phantom {

std::vector<Eigen::Vector3d> WaypointPositions(const ColonAnatomy& anatomy, Posture posture, double deformation) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(anatomy.waypoints.size());
  for (const Waypoint& w : anatomy.waypoints)
    points.push_back(posture == Posture::Prone ? Eigen::Vector3d(w.supine + deformation * w.proneOffset) : w.supine);
  return points;
}

CenterlineCurve SmoothCenterline(const ColonAnatomy& anatomy, Posture posture, double deformation) {
  std::vector<double> radii;
  for (const Waypoint& w : anatomy.waypoints) radii.push_back(w.bendRadius);
  return CenterlineCurve(WaypointPositions(anatomy, posture, deformation), radii, kCenterlineSigmaMm,
                         kCenterlineStepMm, Eigen::Vector3d(0.0, -1.0, 0.0));
}

}  // namespace phantom
}  // namespace colonmap
