#pragma once
// Conformal flattening of one colon segment, a topological cylinder Q with end loops g1, g2,
// cut open along a path d from one loop to the other (DESIGN §2.3; Zeng et al. 2010):
//   f1 harmonic on Q, f1 = 1 on g1, 0 on g2 (cotangent Laplacian of Q);
//   f2 harmonic on the cut surface with a jump of 1 across d, Neumann on g1, g2 (see
//      CutCondition: periodic, i.e. harmonic across d, by default; or 0 / 1 on the two copies);
//   lambda = argmin sum_faces area |grad f1 - lambda n x grad f2|^2
//          = sum area <grad f1, n x grad f2> / sum area |grad f2|^2 (closed form);
//   omega = grad f1 + i lambda grad f2, integrated to phi = (u, v).
// Integration is exact here: omega's two parts are per-face gradients of piecewise-linear
// functions on the cut disk (f1 copied to both sides of the cut), so the integral of omega along
// any edge path from a base vertex is lambda f2 + i f1 up to a constant, with no path
// dependence and no least-squares step. Hence u = lambda f2 (shifted to start at 0), v = f1.
// The sign of lambda follows from the mesh orientation: with right-hand face normals n,
// grad v = n x grad u is what an orientation-preserving conformal map satisfies, so phi keeps
// the faces' orientation whichever side of the cut got f2 = 0.
//
// Normalisation and orientation convention: u runs around the colon over a period W (the low
// copy of the cut has mean u = 0, the high copy mean u = W; exactly [0, W] with a Dirichlet
// cut), v along it in
// [0, W / |lambda|], v = 0 on g2 and v = max on g1. With a CenterlineArcLength array (mm from
// the anal end) g1 is the loop with the larger mean arc length, so v grows towards the cecum in
// both scans; without one g1 is the loop holding the path's first vertex. W = 1 (unit width)
// or the mean circumference in mm (mean length of the f1 isolines at 20 levels), in which case
// u and v are mm-like and the rectangle's area approximates the surface area.
#include "Core/Cancel.h"
#include "Flattening/CutAlongPath.h"

#include <Eigen/Core>

#include <string>
#include <utility>
#include <vector>

namespace colonmap::flattening {

enum class WidthMode { Unit, Circumference };
// How f2 meets the cut.
//  Periodic (default, the exact holomorphic 1-form): f2 jumps by exactly 1 across the cut and
//    is harmonic everywhere, across the cut too (Neumann on g1, g2). Then d f2 is the discrete
//    harmonic 1-form with period 1 around the colon (Gu-Yau), grad f1 ~ lambda n x grad f2
//    holds up to discretisation everywhere, and the cut maps to a curve u = c(v) on one side
//    and c(v) + W on the other: the image is one period of a strip (u and u + W are the same
//    point), its ends exactly at v = 0 and v = max. Any cut path gives the same map up to the
//    choice of the period; no fold where the path runs sideways.
//  Dirichlet (DESIGN §2.3 read literally): f2 = 0 on the left copy of the cut, 1 on the right.
//    The image is an exact rectangle, but f2 is not harmonic across the cut unless the path is
//    a gradient line of f1: distortion concentrates along the cut, and where the path steps
//    back against f1 (sideways steps along mesh edges) the cut side folds over (flipped faces).
enum class CutCondition { Periodic, Dirichlet };

struct FlatteningOptions {
  WidthMode width = WidthMode::Unit;
  int circumferenceLevels = 20;  // f1 isolines averaged for the mean circumference
  CutCondition cut = CutCondition::Periodic;
};

struct FlatteningResult {
  CutMesh cut;             // the cut disk; uv and f2 live on its vertices
  Eigen::MatrixXd uv;      // n' x 2 (u around, v along), scaled as in the options
  Eigen::VectorXd f1;      // n (cylinder vertices)
  Eigen::VectorXd f2;      // n' (cut-mesh vertices)
  double lambda = 0.0;     // signed; the rectangle is 1 x 1/|lambda| before scaling
  double scale = 1.0;      // uv = scale * (u, v) of the unit-width map
  double circumferenceMm = 0.0;  // mean f1-isoline length (units of V)
  double lengthMm = 0.0;         // circumferenceMm / |lambda|
  std::vector<int> g1, g2;       // the end loops (cylinder vertex indices)
  // Seconds per step, in order: checks, laplacian, f1, cut, f2, map.
  std::vector<std::pair<std::string, double>> times;
};

// V, F: the cylinder (one component, Euler characteristic 0, two boundary loops, manifold,
// consistently oriented, every vertex used). path: vertex indices from one loop to the other
// along mesh edges. arcLength: empty, or one value per vertex (orients v, see above).
// progress: Report(fraction) between steps (may throw Cancelled). Throws colonmap::Error with a
// sentence (no input name) when the mesh is not a cylinder or the path not a cut path.
FlatteningResult ConformalFlattening(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F,
                                     const Eigen::VectorXi& path, const Eigen::VectorXd& arcLength,
                                     const FlatteningOptions& options, ProgressSink& progress);

// Per-face gradient (m x 3) of the piecewise-linear function x on (V, F).
Eigen::MatrixXd FaceGradients(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& x);

// Mean length of the isolines x = c for c = (k + 0.5) / levels, k = 0..levels-1, of a
// piecewise-linear x in [0, 1] (e.g. f1: the mean circumference of a cylinder).
double MeanIsolineLength(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& x, int levels);

}  // namespace colonmap::flattening
