#pragma once
// The initial map of the Harmonic method (issue 7), in place of the rectangle affine eta: the two
// segments' mean-curvature images aligned along the colon and around it before any fold is
// matched. Why: on surfaces from our own CT pipeline the affine map is off by up to 0.15 width
// along the colon (the prone colon stretches unevenly, and the flexure cuts land a few mm apart
// in the two scans) and by a shift around the colon that varies along it (the cut taenia is
// tracked with a wobble; in the rectum, which has no taeniae, the two cuts are unrelated), more
// than half the fold spacing, so nearest-fold matching after eta picks wrong neighbours.
//
// Method: both segments are rasterised (Flattening/RasterizeFlatImage) as `around` pixels over
// the width and the same number N of rows over their own length (so the affine map is the
// diagonal), robustly normalised (median/MAD, clipped), smoothed (OpenCV Gaussian, periodic
// around), and each row normalised. A dynamic programme over (supine row i, prone row j, shift
// k) finds the monotone path from (0, 0) to (N-1, N-1) minimising
//   sum (1 - ncc(supine row i, prone row j shifted by k)) + shiftStepCost |k changes|
// with steps (1,1), (1,2), (2,1) (local stretch between 1/2 and 2 of the affine one, the ends
// pinned to the ends), |j - i| <= band rows and |k| <= shiftRange. The path, averaged per supine
// row and smoothed (Gaussian, more where the result would reverse a thin supine triangle that
// straddles a kink), gives the warp
//   W(u, v) = (u + s(v), w(v)),  w strictly increasing, w(ends) = prone ends,
// which is one-to-one (Jacobian determinant w'(v) > 0). Slivers (flat area below 1e-9 of the mean
// face's) do not count as reversed. When every smoothing still reverses a supine face, the warp
// keeps only the path's mean shift around the colon on the affine length map: a rotation of the
// rectangle, one-to-one by construction. Why not the affine map alone: the mean shift corrects a
// cut taenia found one taenia off in one scan (a third of the width). Eigen and Core in and out;
// OpenCV only in the .cxx.
#include "Core/Cancel.h"
#include "Registration/SurfaceMap.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::registration {

struct AlignmentOptions {
  int around = 64;              // pixels around the colon
  double smoothPixels = 1.5;    // Gaussian sigma of the curvature images (pixels)
  double band = 0.4;            // |prone row - supine row| <= band * around rows
  double shiftRange = 0.5;      // |shift| <= shiftRange (width units; 0.5 allows any shift)
  double shiftStepCost = 0.3;   // per pixel of change of the shift from one row to the next
                                // (0.05 let the shift drift in the cecum: 5 seeds, mean 2.7 mm
                                // against 2.2 at 0.3)
  double smoothSigmaRows = 3.0; // Gaussian smoothing of the path (rows); doubled (twice at most)
                                // while the warp reverses a supine face
};

class CurvatureWarp {
 public:
  // Nodes (ascending supine v): supine v -> prone v and shift s (flat units, prone u = u + s).
  std::vector<double> supineV, proneV, shift;
  double scale = 1.0;            // affine length ratio (used beyond the end nodes)
  double pathCorrelation = 0.0;  // mean ncc along the path
  double affineCorrelation = 0.0;  // mean ncc along the diagonal at shift 0 (the affine map)
  int rows = 0;
  double smoothSigmaRows = 0.0;  // the smoothing used
  bool valid = false;            // no supine face reversed by W (else do not use W)
  bool shiftOnly = false;        // W is the affine length map and one shift (see above)

  Eigen::Vector2d Apply(const Eigen::Vector2d& uv) const;
  Eigen::MatrixXd Apply(const Eigen::MatrixXd& uv) const;  // row-wise
  double MeanShift() const;
  double MaxAlongDeviation() const;  // max |w(v) - affine(v)| over the nodes (flat units)
};

// supine/prone: flat segments (period > 0), Hs/Hp: MeanCurvature per vertex. Throws
// colonmap::Error for sizes that do not match. progress: Report(0..1), may throw Cancelled.
CurvatureWarp AlignCurvatureImages(const FlatSegment& supine, const Eigen::VectorXd& Hs, const FlatSegment& prone,
                                   const Eigen::VectorXd& Hp, const AlignmentOptions& options, ProgressSink& progress);

}  // namespace colonmap::registration
