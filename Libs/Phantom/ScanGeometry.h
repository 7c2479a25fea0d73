#pragma once
// One embedding (supine or prone) of the colon material in LPS mm:
//   u = ArcLength(s)             material s -> arc length of this scan's centreline (monotone)
//   X(s, theta) = c(u) + r(s, theta) (cos(theta + tau(s)) N(u) + sin(theta + tau(s)) B(u))
//   r(s, theta) = exp(logD(s, theta)) (R0(s) - folds(s, theta) - polyps(s, theta))
// with (T, N, B) the rotation-minimising frame of the scan's centreline and tau the twist.
// Supine: u = s, tau = 0. Prone: moved control polygon, remapped arc length, twist, distension
// and fold heights all scale with the deformation (0 gives the supine geometry).
#include "CenterlineCurve.h"
#include "ColonAnatomy.h"
#include "Pchip.h"
#include "PhantomOptions.h"

#include <Eigen/Core>
#include <utility>
#include <vector>

namespace colonmap {
namespace phantom {

// A pool of tagged fluid: the lumen below a flat level (a plane perpendicular to gravity) for
// centreline arc lengths in [u0, u1] (the stretch where the lumen floor is below the level).
struct FluidPool {
  double u0 = 0.0, u1 = 0.0;  // scan arc-length range (may extend past the ends: end caps)
  double level = 0.0;         // height of the air-fluid level, Height(p) = -Down().dot(p)
  double deepestU = 0.0;      // arc length of the pool's deepest point
};

class ScanGeometry {
 public:
  ColonAnatomy anatomy;
  Posture posture = Posture::Supine;
  double deformation = 0.0;
  CenterlineCurve centerline;
  bool identityRemap = true;  // supine: u == s exactly
  Pchip arcOfS;               // material s -> scan arc length u
  Pchip twist;                // s -> tau (rad)
  Pchip logDistension, ellipticity, ellipseAngle;  // prone change of the cross-section
  std::vector<FluidPool> pools;
  std::vector<std::pair<double, double>> collapsedU;  // arc-length ranges of this scan's collapsed stretches
  double fluidHU = 750.0;

  double ArcLength(double s) const { return identityRemap ? s : arcOfS(s); }
  double MaterialS(double u) const { return identityRemap ? u : arcOfS.Inverse(u); }
  // du/ds: local longitudinal stretch of this scan relative to the supine one.
  double Stretch(double s) const { return identityRemap ? 1.0 : arcOfS.Derivative(s); }
  double Twist(double s) const { return twist.Empty() ? 0.0 : twist(s); }

  // Log of the radius scale at (s, theta) (supine ellipticity plus prone change).
  double LogDistension(double s, double theta) const;
  // Distended base radius without folds and polyps.
  double BaseRadius(double s, double theta) const;
  // Lumen surface radius r(s, theta).
  double WallRadius(double s, double theta) const;
  // Outer wall surface radius (base radius + wall thickness; folds are mucosal).
  double OuterRadius(double s, double theta, double wallThickness) const;

  Eigen::Vector3d CenterPoint(double s) const { return centerline.Point(ArcLength(s)); }
  // Direction from the centreline for (s, theta): unit vector in the normal plane at ArcLength(s).
  Eigen::Vector3d RadialDirection(double s, double theta) const;
  // Point X(s, theta) on the lumen surface.
  Eigen::Vector3d WallPoint(double s, double theta) const;

  // Gravity: supine +y (posterior is down), prone -y.
  Eigen::Vector3d Down() const { return Eigen::Vector3d(0.0, posture == Posture::Supine ? 1.0 : -1.0, 0.0); }
  double Height(const Eigen::Vector3d& p) const { return -Down().dot(p); }
  // Pool whose arc-length range contains u, or nullptr.
  const FluidPool* PoolAt(double u) const;
  // How far (mm of arc length) u lies inside a collapsed stretch of this scan: positive inside,
  // negative outside (the distance to the nearest one), -inf without collapses.
  double CollapseDepth(double u) const;
};

// Builds a scan's embedding. options.deformation and options.seed (fluid pools) are used.
ScanGeometry MakeScan(const ColonAnatomy& anatomy, Posture posture, const PhantomOptions& options);

}  // namespace phantom
}  // namespace colonmap
