#pragma once
// The centreline of a scan from the anatomy's control polygon: shared by MakeAnatomy (which
// defines material s on the supine curve) and MakeScan, so both build exactly the same curve.
#include "CenterlineCurve.h"
#include "PhantomOptions.h"

#include <Eigen/Core>
#include <vector>

namespace colonmap {
namespace phantom {

struct ColonAnatomy;

// Smoothing length (mm) after the corners are rounded (makes the curvature continuous), and
// sample step of the curve.
constexpr double kCenterlineSigmaMm = 5.0;
constexpr double kCenterlineStepMm = 1.0;

// Control polygon of a scan: supine positions, plus deformation * proneOffset when prone.
std::vector<Eigen::Vector3d> WaypointPositions(const ColonAnatomy& anatomy, Posture posture, double deformation);

// The centreline of a scan: the control polygon with corners rounded to the waypoints' bend
// radii, smoothed; the frame starts pointing anteriorly.
CenterlineCurve SmoothCenterline(const ColonAnatomy& anatomy, Posture posture, double deformation);

}  // namespace phantom
}  // namespace colonmap
