#pragma once
// Conformal flattening of one colon segment, a topological cylinder Q with end loops g1, g2,
// cut open along a path d from one loop to the other (DESIGN §2.3; Zeng et al. 2010):
//   f1 harmonic on Q, f1 = 1 on g1, 0 on g2 (cotangent Laplacian of Q);
//   f2 harmonic on the cut surface with a jump of 1 across d, Neumann on g1, g2 (see
//      CutCondition: periodic, i.e. harmonic across d, by default; or 0 / 1 on the two copies);
//   lambda = argmin sum_faces area |grad f1 - lambda n x grad f2|^2
//          = sum area <grad f1, n x grad f2> / sum area |grad f2|^2 (closed form). The
//      numerator is the signed area of the image of the cut disk under (f2, f1) (Green: it does
//      not depend on the triangulation), the denominator f2's Dirichlet energy -f2' Lc f2 / 2 with
//      the Laplacian the harmonic functions were solved with;
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
#include <Eigen/SparseCore>

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
// What f2 (periodic cut) satisfies on the end loops g1, g2.
//  ConjugateFlux (default): Dirichlet values that rise monotonically along each loop, by the flux
//    of f1 through it (u(x) = flux of f1 through the loop between the cut and x, over the total):
//    the discrete form of the Cauchy-Riemann relation du/ds = dv/dn on the boundary, so in the
//    limit the same map as Neumann ends. The twist of one loop against the other is then chosen
//    to minimise the Dirichlet energy (adding c f1). Why: with Neumann ends and an end loop that
//    zig-zags along mesh edges (the landmarks stage closes its cut loops along edges), u runs
//    backwards along short boundary edges, and the faces on them flip (measured: nearly all the
//    flipped faces of the phantom pipeline's segments were such end-loop faces). With monotone u
//    on the loops, v constant there and positive weights (intrinsic Delaunay), every face is
//    a convex combination map of an annulus onto a flat cylinder with straight monotone
//    boundaries (Tutte / Floater), so nothing folds. f1 and f2 then share one factorisation
//    (the same constrained vertices), which also halves the solve time.
//  Neumann: natural boundary condition (harmonic up to the loop), a second factorisation.
enum class EndCondition { ConjugateFlux, Neumann };
// Which cotangent Laplacian the harmonic functions use.
//  IntrinsicDelaunay (default): that of the intrinsic Delaunay triangulation of the same surface
//    (IntrinsicDelaunay.h: edge flips, no vertex moves; the cut path's edges are kept). All its
//    weights are >= 0 but for the few edges that cannot be flipped, so f1 and f2 obey the
//    discrete maximum principle and the map does not fold where the mesh has obtuse or sliver
//    triangles (measured: Benchmark/FlatteningSurvey, docs/performance.md). The map is still
//    evaluated at the mesh's vertices and drawn on the mesh's own faces.
//  Mesh: the mesh's own cotangent weights (negative on edges opposite two obtuse angles).
enum class LaplacianMode { IntrinsicDelaunay, Mesh };

struct FlatteningOptions {
  WidthMode width = WidthMode::Unit;
  int circumferenceLevels = 20;  // f1 isolines averaged for the mean circumference
  CutCondition cut = CutCondition::Periodic;
  LaplacianMode laplacian = LaplacianMode::IntrinsicDelaunay;
  EndCondition ends = EndCondition::ConjugateFlux;  // with CutCondition::Periodic only
};

struct FlatteningResult {
  // The cut disk; uv and f2 live on its vertices (the input's, then one copy per path vertex).
  // Its faces are those the map was computed on: the input's with LaplacianMode::Mesh; with
  // IntrinsicDelaunay the intrinsic Delaunay faces (same vertices, same face count, changedFaces
  // of them differ from the input's, drawn as straight triangles within edgeGapBound of the
  // surface), so that the fold-free guarantee holds for the faces one draws and measures.
  CutMesh cut;
  Eigen::MatrixXd uv;      // n' x 2 (u around, v along), scaled as in the options
  Eigen::VectorXd f1;      // n (cylinder vertices)
  Eigen::VectorXd f2;      // n' (cut-mesh vertices)
  double lambda = 0.0;     // signed; the rectangle is 1 x 1/|lambda| before scaling
  double scale = 1.0;      // uv = scale * (u, v) of the unit-width map
  double circumferenceMm = 0.0;  // mean f1-isoline length (units of V)
  double lengthMm = 0.0;         // circumferenceMm / |lambda|
  std::vector<int> g1, g2;       // the end loops (cylinder vertex indices)
  // Intrinsic Delaunay (LaplacianMode::IntrinsicDelaunay; 0 otherwise): edges flipped, and
  // edges with a negative cotangent weight on the mesh and on the triangulation used.
  long edgeFlips = 0, negativeWeightsMesh = 0, negativeWeightsUsed = 0;
  long negativeWeightsOnCut = 0;  // of negativeWeightsUsed: on the (kept) cut path's edges
  long changedFaces = 0;          // IntrinsicDelaunay: faces not in the input
  double edgeGapBound = 0.0;      // IntrinsicDelaunay: bound on the drawn edges' distance to the surface
  long nonPositiveFlux = 0;  // loop vertices whose f1 flux was <= 0 and was raised (ConjugateFlux)
  // Seconds per step, in order: checks, laplacian (incl. the Delaunay flips), f1, cut, f2, map.
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

// The ConjugateFlux end values of f2 (see EndCondition): one value per vertex of g1 then g2 (in
// their order), 0 at the cut's left copy rising to 1 at its right copy. L: the Laplacian f1 was
// solved with; cut: the mesh cut along path (its faces tell which way round is left to right).
// nonPositive (optional): loop vertices whose flux was <= 0 and was raised to a small share.
Eigen::VectorXd ConjugateFluxEndValues(const Eigen::SparseMatrix<double>& L, const Eigen::VectorXd& f1, const CutMesh& cut,
                                       const Eigen::VectorXi& path, const std::vector<int>& g1, const std::vector<int>& g2,
                                       long* nonPositive = nullptr);

// Per-face gradient (m x 3) of the piecewise-linear function x on (V, F).
Eigen::MatrixXd FaceGradients(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& x);

// Mean length of the isolines x = c for c = (k + 0.5) / levels, k = 0..levels-1, of a
// piecewise-linear x in [0, 1] (e.g. f1: the mean circumference of a cylinder).
double MeanIsolineLength(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& x, int levels);

}  // namespace colonmap::flattening
