#pragma once
// Centreline of a closed tubular surface (the colon lumen) between its two geodesic
// extremities, centred in the lumen and smoothed, with arc length.
//
// Method: the two ends are the farthest pair in edge-graph geodesic distance (double sweep of
// Dijkstra). The centroids of the geodesic level sets from one end (area weighted, bins of
// stepMm) give a first curve inside the tube; it is then re-centred a few times: every vertex
// is projected onto the current curve (Analysis/MidlineProjection) and each curve sample moves
// to the area-weighted centroid of the wall that projects onto it, followed by Gaussian
// smoothing along the arc. That re-centring is off by default: thin projection slices at a bend
// are fan-shaped and their centroids lie outside the bend, so the passes amplified bends (the
// phantom centreline grew from 1.3 m to 3 m in three passes); the smoothed level-set centroids
// alone came within 1-3% of the true length. Those centroids still cut the inside of every
// bend, so the smoothed curve is then moved onto the lumen's medial line (CentreInLumen.h) and
// smoothed again; the level-set curve is kept as `uncentred`. The curve runs from endFirst to endSecond; the caller orients it.
#include "Core/Cancel.h"
#include "Landmarks/CentreInLumen.h"

#include <Eigen/Core>

namespace colonmap::landmarks {

struct CenterlineOptions {
  double levelBinMm = 8.0;    // bin width of the geodesic level sets (first curve)
  double stepMm = 4.0;        // bin width of the re-centring samples
  double smoothingMm = 8.0;   // Gaussian sigma along the arc
  int iterations = 0;         // re-centring passes (off: slice centroids amplify bends; see .cxx)
  double outputStepMm = 1.0;  // spacing of the returned samples
  bool centre = true;         // move the curve onto the medial line (CentreInLumen.h)
  CentringOptions centring;
  double centredSmoothingMm = 10.0;  // Gaussian sigma along the arc after centring
};

struct Centerline {
  Eigen::MatrixXd points;  // k x 3, evenly spaced (outputStepMm), from endFirst to endSecond
  Eigen::VectorXd arc;     // cumulative arc length, arc(0) = 0
  int endFirst = -1, endSecond = -1;  // the geodesic extremities (vertex ids)
  // Mean distance to the wall (mm) of the level-set curve and of the returned (centred) curve.
  double clearanceBeforeMm = 0, clearanceMm = 0;
  // When centred: the smoothed level-set curve before centring (outputStepMm, same direction),
  // on which the flexure rules were tuned; empty otherwise.
  Eigen::MatrixXd uncentred;
  double Length() const { return arc.size() ? arc(arc.size() - 1) : 0.0; }
};

// V, F: a closed, connected surface. progress: fractions 0..1 of this step.
Centerline ComputeCenterline(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const CenterlineOptions& options,
                             ProgressSink& progress);

// The same curve reversed (arc recomputed from the new first point).
Centerline Reversed(const Centerline& c);

// Polyline helpers: resample at an even step (first and last points kept), Gaussian smoothing
// of an evenly sampled polyline, or of any sampled signal with one column per value (sigma in
// samples; end points are kept in place).
Eigen::MatrixXd ResamplePolyline(const Eigen::MatrixXd& P, double step);
Eigen::MatrixXd SmoothPolyline(const Eigen::MatrixXd& P, double sigmaSamples);

}  // namespace colonmap::landmarks
