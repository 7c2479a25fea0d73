#pragma once
// Material coordinates of a real colon (issue 17): a smooth along-colon coordinate s that is
// monotone along the tube however tight the bends or close the loops, and an angle theta
// around it, on the closed genus-0 lumen surface opened at its two ends.
//
// Method. A nearest-midline-point projection jumps wherever the midline bends tighter than the
// lumen radius or two loops touch (a wall point is then nearer to another stretch of midline).
// Instead s comes from one harmonic function on the surface, which knows only the surface:
//  1. f harmonic on the closed surface, f = 0 on a geodesic disc around the caecal pole and
//     f = 1 on one around the anal tip (the two tips of the tube: from the vertex nearest the
//     anus hint, the geodesically farthest vertex, and the one farthest from that; intrinsic Delaunay cotangent Laplacian with its few
//     negative weights raised, Flattening/IntrinsicDelaunay.h, so the discrete maximum principle
//     holds: f has no interior extremum).
//  2. The surface is cut along the levels f = endLevel and 1 - endLevel (Landmarks/IsoLines.h);
//     the faces between them are the open tube, a topological cylinder whose boundary loops are
//     level sets. On it f is harmonic with constant values on both loops: no interior critical
//     point, so every level set is one loop and two levels never meet.
//  3. The centroids of `levels` level sets, smoothed along the sequence, form the supine
//     centreline; s of a level is the arc length of that curve from the caecal end (0) to the
//     anal end (the colon length), and s of a vertex is interpolated from its f: monotone in f
//     by construction.
//  4. theta = angle of (vertex - centreline point at its s) in the centreline's rotation-
//     minimising frame (Analysis/MidlineProjection.h), in [0, 2 pi).
// Checks reported: interior tube vertices that are a local extremum of f among their mesh
// neighbours (a closed level loop, i.e. a non-monotone spot; the few the harmonic solution has
// take their neighbours' mean), and the largest number of curves in any of a sample of level
// sets.
#include "Core/Cancel.h"
#include "Core/TriangleMesh.h"
#include "Landmarks/LevelCentreline.h"

#include <Eigen/Core>
#include <vector>

namespace colonmap::realcolon {

struct MaterialOptions {
  double endDiscMm = 10.0;   // geodesic radius of the Dirichlet discs at the two ends
  double endLevel = 0.01;    // the tube is cut at f = endLevel and f = 1 - endLevel
  int levels = 4000;         // level sets that define the centreline
  double smoothingMm = 4.0;  // Gaussian sigma along the centroid sequence (removes haustral wiggle)
  int checkedLevels = 400;   // level sets whose curves are counted (monotonicity check)
};

struct TubeMaterial {
  TriangleMesh closed;          // the input with the two cut loops' vertices appended (orientation kept)
  Eigen::VectorXd closedF;      // harmonic value per closed vertex (0 caecal disc .. 1 anal disc)
  std::vector<bool> tubeFace;   // faces of `closed` between the cuts
  std::vector<int> tubeVertex;  // tube vertex -> closed vertex
  TriangleMesh tube;            // the open tube (a cylinder), same orientation, no arrays
  Eigen::VectorXd f;            // per tube vertex: closedF rescaled to [0, 1] (0 caecal loop, 1 anal loop)
  Eigen::VectorXd s, theta;     // per tube vertex (mm, rad)
  // The supine centreline: level f of each sample, its smoothed centroid, its s, loop radius.
  Eigen::VectorXd levelF, levelS, levelRadius, levelMaxRadius;
  Eigen::MatrixXd centroid;
  double length = 0.0;          // s at the anal loop
  // Monotonicity.
  long harmonicExtrema = 0;     // interior tube vertices above or below all their mesh neighbours in
                                // the harmonic solution (the intrinsic triangulation's neighbours
                                // differ from the mesh's); each then takes its neighbours' mean
  long localExtrema = 0;        // ... left after that (0 expected)
  int maxCurvesPerLevel = 0;    // over the checked levels (1: each level set is one loop)
  int checkedLevels = 0;

  Eigen::MatrixXd frameN, frameB;  // rotation-minimising frame per centreline segment

  double SOfF(double f) const;                              // piecewise linear in (levelF, levelS)
  double FOfS(double s) const;                              // its inverse
  Eigen::Vector3d CentrePoint(double s) const;              // centreline point at s
  double Angle(const Eigen::Vector3d& p, double s) const;   // theta of a wall point p at material s
};

// The level-set centreline of one embedding of the tube (Landmarks/LevelCentreline.h).
using landmarks::ComputeLevelCentreline;
using landmarks::LevelCentreline;

// closed: closed, connected, manifold, genus-0 surface (normals into the lumen), mm.
// caecalPole, anus: points near the two ends (which tip is which).
// Throws colonmap::Error when the surface is not such a surface or the ends coincide.
TubeMaterial MakeTubeMaterial(const TriangleMesh& closed, const Eigen::Vector3d& caecalPole, const Eigen::Vector3d& anus,
                              const MaterialOptions& options, ProgressSink& progress);

}  // namespace colonmap::realcolon
