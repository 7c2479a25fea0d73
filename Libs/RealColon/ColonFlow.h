#pragma once
// The supine -> prone deformation of a real colon (issue 17): the tube phantom's model (mobile
// transverse and sigmoid loops, fixed segments moving 6-12 mm, local stretch, torsion, radius
// change, fold height change; Phantom/ColonAnatomy.h), applied as the flow of a smooth velocity
// field so that the map is one-to-one and the prone colon cannot pass through itself, even
// where loops of a real colon touch.
//
// Control frames every controlStepMm along the supine centreline each carry a rigid-plus-radial
// velocity: a translation (the seeded displacement of that centreline point plus a slide along
// the tangent), a rotation (twist about the tangent, plus the rotation that keeps cross-sections
// perpendicular to the moving centreline), a radial scaling (distension) and a scaling of the
// wall's radial deviation from the loop radius (fold heights). The velocity at any point is the
// Wendland-weighted (compact, C2) average of the frames' velocities around it, the frames being
// carried by the flow themselves; integrated from t = 0 to 1 (RK4). A frame's weight reaches
// beyond its own wall (the loop's farthest point, at least 1.5 x its mean radius, plus 10 mm),
// so loops of the colon interact only where they come close. A C2 velocity field has a
// flow that is a diffeomorphism of space: the prone surface is the image of the supine one, so
// it stays embedded (checked by RealColon/SelfIntersection.h anyway), and loops that touch move
// together where they touch.
#include "Core/Cancel.h"
#include "RealColon/TubeMaterial.h"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <vector>

namespace colonmap::realcolon {

struct FlowControl {
  double s = 0.0;                 // material s of the frame
  int segment = 0;                // 0..4 = A, T, D, S, R
  Eigen::Vector3d centre{0, 0, 0};  // supine centreline point
  double radius = 20.0;           // mean loop radius there (mm)
  double support = 50.0;          // radius of the frame's weight (mm): just beyond its wall
  Eigen::Vector3d displacement{0, 0, 0};  // translation over the flow (mm)
  double slide = 0.0;             // extra translation along the tangent (mm): local stretch
  double twist = 0.0;             // rotation about the tangent (rad)
  double logDistension = 0.0;     // radial log scale
  double foldLogScale = 0.0;      // log scale of the wall's deviation from the loop radius
};

struct ColonFlow {
  std::vector<FlowControl> controls;
  int steps = 4;  // RK4 steps from t = 0 to 1 (measured on GCA 00020: within 2 um of 16 steps)
  // The images of the points (n x 3) at t = 1. Deterministic and independent of the thread count.
  // progress (optional): fractions per RK stage, and its Cancelled.
  Eigen::MatrixXd Apply(const Eigen::MatrixXd& points, ProgressSink* progress = nullptr) const;
  double Support(std::size_t k) const { return controls[k].support; }
};

struct FlowOptions {
  double deformation = 0.5;     // 0: identity; 0.5 the default strength; 1 strong
  double controlStepMm = 10.0;  // spacing of the control frames along s
};

// The seeded prone flow of a colon with material coordinates `m` and flexures at flexureS
// (HF, SF, DSJ, RSJ, increasing). At deformation 0.5 (the default): fixed segments move by a
// global shift of 3-6 mm plus a jitter of up to 5 mm along the colon, the transverse loop's
// middle by 18-32 mm more (mostly anterior and caudal) and the sigmoid's by 18-30 mm, both
// falling to the fixed motion at their flexures (chosen so that "no registration" lands near
// 8-15 mm mean with the transverse and sigmoid above 15 mm, issue 17); twist, distension, fold heights and slide as the tube phantom at the same
// deformation. Amplitudes scale with the deformation (translations linearly from 0.5). Where
// the flow would stretch or compress the centreline by more than 10% over a control interval
// (a loop shifted along itself near its flexure, or tethered where it nearly touches a fixed
// loop), a compensating slide along the tangent takes the excess back: the colon bends rather
// than stretches.
ColonFlow MakeProneFlow(const TubeMaterial& m, const std::array<double, 4>& flexureS, std::uint32_t seed,
                        const FlowOptions& options);

// Stretch of each interval between consecutive frames under the flow: length of the image of
// the supine centreline (m.CentrePoint) over the interval / its supine length - 1.
std::vector<double> IntervalStrain(const ColonFlow& flow, const TubeMaterial& m);

}  // namespace colonmap::realcolon
