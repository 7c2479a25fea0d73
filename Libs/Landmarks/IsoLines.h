#pragma once
// Level sets of a piecewise-linear function f on a triangle mesh (f given per vertex, linear on
// each face), libigl style: Eigen in and out.
//
// A vertex counts as above a level when f >= level, so every face with corners on both sides
// meets the level in exactly one segment, between the crossing points of its two mixed edges.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>
#include <vector>

namespace colonmap::landmarks {

// Cuts the mesh along {f = level}: every edge whose ends lie strictly on both sides gets a new
// vertex at the crossing (f = level there exactly; point arrays interpolated, see
// flattening::SplitEdgesAt), so that the level set becomes a chain of mesh edges and no face
// has corners strictly on both sides. f grows with the new vertices. Returns their indices
// (appended after the existing ones). Cell arrays are dropped when anything was split.
std::vector<int> CutAtLevel(TriangleMesh& mesh, Eigen::VectorXd& f, double level);

// One connected piece of a level set, as a polyline of crossing points.
struct LevelCurve {
  Eigen::MatrixXd points;  // k x 3
  bool closed = false;     // a loop (false: it ends on the mesh boundary)
  double Length() const;
};

// The level set {f = level} as curves, chained through shared edges. Deterministic order.
std::vector<LevelCurve> LevelSet(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& f,
                                 double level);

// Summary of many level sets in one pass over the faces (levels sorted increasingly).
struct LevelSummary {
  Eigen::MatrixXd centroid;  // levels x 3: length-weighted centroid of the level set (NaN if empty)
  Eigen::VectorXd length;    // total length of the level set
  Eigen::VectorXd meanRadius;  // mean distance of the set's points from its centroid (length weighted)
  Eigen::VectorXd maxRadius;   // largest distance of a crossing point from the centroid
  Eigen::MatrixXd lowest;    // levels x 3: the crossing point that lies lowest along `down`
};
// down: the direction of gravity (for `lowest`); any unit vector when not needed.
LevelSummary SummarizeLevels(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& f,
                             const Eigen::VectorXd& levels, const Eigen::Vector3d& down);

}  // namespace colonmap::landmarks
