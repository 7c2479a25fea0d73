#pragma once
// The four flexures of the colon on its centreline: hepatic (HF, A-T), splenic (SF, T-D),
// descending-sigmoid (DSJ, D-S) and sigmoid-rectum (RSJ, S-R) junctions.
//
// Method (the paper orders the major bends by height; we add left/right and the shape of the
// height profile; LPS: +x is patient left, +y posterior, +z superior). Rules on the height
// profile z(s) use a hysteresis of heightHysteresisMm, so that the small rises and dips of a
// real, tortuous colon do not end a run (the GCA descending colon wanders +-50 degrees off the
// vertical over 600 mm but never rises on our centreline; its sigmoid rises 18 mm after the DSJ).
//   SF  = the highest centreline point on the left half (x above the middle of the x range),
//         moved to the sharpest bend (turning angle over +-bendScaleMm) within +-refineMm;
//   HF  = the top of the ascending colon's climb: walking from the cecal end, the first peak of
//         z (after the first rise of more than the hysteresis, so a horizontal or sinking
//         caecal pole does not count), moved back toward the cecum to the last point that still
//         climbs at more than hepaticClimbDeg (the colon levels off into the transverse there);
//   DSJ = where the descending colon leaves the left paracolic gutter: walking from SF toward
//         the anus, the descent ends at the first trough of z (hysteresis); in the lowest
//         descendingLowerFraction of that descent, the first point where the colon turns
//         anterior and medial (the sigmoid runs forward and to the midline on its mesocolon;
//         unit direction of travel t over +-turnTangentMm: (-t_y - sigmoidMedialWeight t_x) /
//         |(1, sigmoidMedialWeight)| above sigmoidTurn, where it descends at most sigmoidSlowing
//         times as steeply as the descending colon above (median vertical part of travel) and
//         no steeper than sigmoidMaxDescentDeg: a descending colon that turns forward or medially
//         as it plunges on is still the descending colon, as on the HuBMAP male and female
//         colons, whose atlases put the DSJ at the bottom of the descent), else the trough
//         itself. (The tube phantom's generator puts its DSJ where its fixed descending colon
//         meets the mobile sigmoid, 60-80 mm above the bottom of the descent: another convention;
//         its check uses the bottom of its true descent, Testing/LandmarksPhantomTest.)
//   RSJ = going up the rectum from its most vertical point (within rectumSearchMm of the anal
//         end; the anal canal leans), the first point where the
//         direction leaves +z by more than the exit angle (before the DSJ).
// Why not fixed distances or vertical-exit angles for HF and DSJ: on the real GCA colon the
// caecum runs horizontally for ~80 mm (an exit-angle walk from the cecum fired next to it,
// HF +311 mm) and the descending colon is tilted 35-55 degrees over long stretches (the
// exit-angle walk from SF stopped 70 mm below it, DSJ +512 mm).
// The phantom check (Testing/LandmarksPhantomTest) measures these against the truth.
// Anything missing or out of order is an Error saying what was found.
#include <Eigen/Core>

#include <array>
#include <string>

namespace colonmap::landmarks {

struct FlexureOptions {
  double bendScaleMm = 40.0;
  double refineMm = 40.0;
  double tangentMm = 20.0;       // chord half-length of the direction of travel (RSJ)
  double turnTangentMm = 10.0;   // the same for the HF and DSJ rules
  double heightHysteresisMm = 10.0;  // a peak or trough of z must be this prominent
  double hepaticClimbDeg = 3.0;       // HF: the last point climbing steeper than this
  double descendingLowerFraction = 0.25;  // DSJ: searched in this lowest part of the descent
  double sigmoidTurn = 0.5;           // DSJ: anterior-medial component of travel above this
  double sigmoidMedialWeight = 0.5;   // weight of the medial (-x) part in that component
  double sigmoidSlowing = 0.8;        // DSJ: the turn counts only where the descent is this much slower
  double sigmoidMaxDescentDeg = 10.0; // DSJ: ... and descends no steeper than this (degrees
                                      // below the horizontal; 10 and 20 put every DSJ of the
                                      // three atlas colons within 40 mm, 90 was the rule before;
                                      // it is the tighter of the two wherever the descending
                                      // colon's median descent is steeper than about 12 degrees)
  double rectumExitDeg = 45.0;   // turn away from the vertical that ends the rectum
  double minRectumMm = 40.0;     // where the RSJ walk starts when no vertical stretch is found
  double rectumSearchMm = 100.0;  // the RSJ walk starts at the most vertical point this near the anus
};

struct Flexures {
  // Order HF, SF, DSJ, RSJ (Names()). Arc length from the anal end (mm) and centreline sample.
  std::array<double, 4> arc{};
  std::array<int, 4> sample{};
  std::array<Eigen::Vector3d, 4> position;
  static const std::array<const char*, 4>& Names();
};

// Turning angle (degrees) at each sample of an evenly spaced polyline between the chords to the
// samples `w` before and after (clamped at the ends).
Eigen::VectorXd BendAngles(const Eigen::MatrixXd& P, int w);

// The DSJ as the atlases place it, on a true centreline (for checks against a phantom whose own
// DSJ follows another convention): the sample of P (n x 3, LPS) with the lowest z among those whose
// arc lies strictly between arcFrom and arcTo (the true SF and RSJ, either order); -1 if none.
Eigen::Index LowestBetween(const Eigen::MatrixXd& P, const Eigen::VectorXd& arc, double arcFrom, double arcTo);

// centerline: evenly spaced samples from the anal end to the cecum; arc: their arc length.
Flexures FindFlexures(const Eigen::MatrixXd& centerline, const Eigen::VectorXd& arc, const FlexureOptions& options = {});

}  // namespace colonmap::landmarks
