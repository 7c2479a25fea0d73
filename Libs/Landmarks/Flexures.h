#pragma once
// The four flexures of the colon on its centreline: hepatic (HF, A-T), splenic (SF, T-D),
// descending-sigmoid (DSJ, D-S) and sigmoid-rectum (RSJ, S-R) junctions.
//
// Method (the paper orders the major bends by height; we add left/right, LPS: +x is patient
// left, +z superior): with `bend(i)` the turning angle of the centreline at sample i over
// +-bendScaleMm of arc,
//   SF  = the highest centreline point on the left half (x above the middle of the x range),
//   HF  = the highest point on the right half on the cecum side of SF,
//   SF moved to the sharpest bend within +-refineMm;
//   HF  = going from the cecum (past cecumSkipMm) up the ascending colon, the first point
//         where the direction of travel (chord over +-tangentMm) leaves +z by more than
//         the exit angle (it must lie on the cecum side of SF);
//   DSJ = going from SF (past splenicBendMm) down the descending colon, the first point where
//         the direction leaves -z by more than the exit angle;
//   RSJ = going up the rectum from its most vertical point (within rectumSearchMm of the anal
//         end; the anal canal leans), the first point where the
//         direction leaves +z by more than the exit angle (before the DSJ).
// The phantom check (Testing/LandmarksPhantomTest) measures these against the truth.
// Anything missing or out of order is an Error saying what was found.
#include <Eigen/Core>

#include <array>
#include <string>

namespace colonmap::landmarks {

struct FlexureOptions {
  double bendScaleMm = 40.0;
  double refineMm = 40.0;
  double tangentMm = 20.0;
  // Turn away from the vertical that ends the ascending colon, descending colon, rectum.
  double hepaticExitDeg = 60.0;
  double descendingExitDeg = 35.0;
  double rectumExitDeg = 45.0;
  double splenicBendMm = 60.0;  // skip this much below SF before looking for the DSJ
  double cecumSkipMm = 30.0;    // and this much of the cecum before looking for the HF
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

// centerline: evenly spaced samples from the anal end to the cecum; arc: their arc length.
Flexures FindFlexures(const Eigen::MatrixXd& centerline, const Eigen::VectorXd& arc, const FlexureOptions& options = {});

}  // namespace colonmap::landmarks
