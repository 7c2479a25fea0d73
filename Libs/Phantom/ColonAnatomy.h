#pragma once
// The colon as material: everything that does not depend on the posture. Material coordinates
// are s (mm along the colon, cecum s = 0 to anus s = length; s is the arc length of the supine
// centreline) and theta (radians around, measured from the scan's frame plus its twist).
// Also holds the seeded draws that shape the prone embedding (per-waypoint displacements,
// stretch, twist and distension at deformation 1), so that MakeScan is a pure function of
// (anatomy, posture, deformation).
#include "Pchip.h"
#include "PhantomOptions.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace colonmap {
namespace phantom {

// A corner of the centreline's control polygon with its seeded prone behaviour.
struct Waypoint {
  Eigen::Vector3d supine{0, 0, 0};       // LPS mm
  int segment = kAscending;              // segment the waypoint lies in
  int flexure = -1;                      // FlexureId if this waypoint is a flexure corner
  double s = 0.0;                        // material s of its nearest supine centreline point
  Eigen::Vector3d proneOffset{0, 0, 0};  // prone displacement at deformation 1 (mm)
  double bendRadius = 40.0;              // wanted bend radius of the centreline at this corner
  double proneTwist = 0.0;               // extra torsion at deformation 1 (rad)
  double logDistension = 0.0;            // prone/supine log radius change at deformation 1
  double ellipticity = 0.0;              // prone anisotropic log radius amplitude at deformation 1
  double ellipseAngle = 0.0;             // its orientation (rad)
};

// A haustral fold (crescent ridge between two taeniae) or a rectal (Houston) valve.
struct Fold {
  double s = 0.0;          // crest position (mm)
  double halfWidth = 4.0;  // half extent along s (raised-cosine profile)
  double height = 5.0;     // supine crest height (mm, inwards)
  double proneLogScale = 0.0;  // log of the prone/supine height ratio at deformation 1
  int sector = 0;          // 0..2: between taenia k and k+1; -1: rectal valve
  double valveTheta = 0.0;     // valves only: centre angle
  double valveHalfAngle = 0.0; // valves only: half angular extent
};

struct Polyp {
  std::string label;        // "P1".."Pn"
  double s = 0.0, theta = 0.0;
  double diameter = 6.0;    // mm (head diameter)
  bool pedunculated = false;
  double height = 3.0;      // radial height of the bump (mm)
  double footRadius = 3.6;  // radius of the bump's base in the (s, R0*theta) plane (mm)
};

// A stretch of colon whose lumen is closed (collapsed or poorly distended: wall touching, no
// air) in one scan or both (issue 21). Material s; the true wall still runs through it.
struct CollapsedStretch {
  double s0 = 0.0, s1 = 0.0;  // material s range (mm)
  bool supine = false, prone = false;  // collapsed in this scan
  int segment = 0;            // segment of its middle
};

struct EvaluationSite {
  std::string label;  // "E001"...
  double s = 0.0, theta = 0.0;
};

struct ColonAnatomy {
  std::uint32_t seed = 0;
  std::vector<Waypoint> waypoints;
  double length = 0.0;                 // L (mm)
  std::array<double, 4> flexureS{};    // HF, SF, DSJ, RSJ (material s)
  Pchip radius;                        // base radius R0(s) (mm)
  double taeniaPhase = 0.0;            // theta of TL at s = 0
  double taeniaTwist = 0.0;            // total helical twist of the taeniae from 0 to s_RSJ (rad)
  double supineEllipticity = 0.0;      // supine cross-section log-radius amplitude
  Pchip supineEllipseAngle;            // its orientation along s
  std::vector<Fold> folds;             // sorted by s
  double maxFoldHalfWidth = 0.0;
  std::vector<Polyp> polyps;
  std::vector<EvaluationSite> evaluationSites;
  // Prone arc-length remap at deformation 1: relative shifts of the knots at 1/4, 1/2, 3/4 of
  // each segment (segment-major), in units of a quarter segment length.
  std::array<double, 15> proneStretch{};
  std::vector<CollapsedStretch> collapses;  // options.collapses of them, sorted by s

  // The stretch collapsed in this posture that contains material s, or nullptr.
  const CollapsedStretch* CollapsedAt(double s, Posture posture) const;

  int SegmentOf(double s) const;
  double BaseRadius(double s) const { return radius(s); }
  // Angle of taenia k (0 TL, 1 TO, 2 TM) at s; the helix stops twisting at the RSJ.
  double TaeniaTheta(int k, double s) const;
  // Inward depth of folds at (s, theta); foldScaleExponent multiplies each fold's
  // proneLogScale (0 for supine, the deformation for prone).
  double FoldDepth(double s, double theta, double foldScaleExponent) const;
  // Inward depth of polyps at (s, theta).
  double PolypDepth(double s, double theta) const;
  // Upper bound of FoldDepth + PolypDepth over all theta for s' in [s - ds, s + ds].
  double MaxDepthNear(double s, double ds, double foldScaleExponent) const;
};

// Builds the anatomy from the seed (options.seed, options.evaluationPoints are used).
ColonAnatomy MakeAnatomy(const PhantomOptions& options);

// Wraps an angle into [0, 2 pi).
double WrapAngle(double a);
// Signed angle difference a - b wrapped into (-pi, pi].
double AngleDifference(double a, double b);

}  // namespace phantom
}  // namespace colonmap
