#pragma once
// Haustral fold features of one flattened colon segment (DESIGN §2.4, issue 7): folds are the
// ridges of high mean curvature. A vertex belongs to a fold when its MeanCurvature (positive on
// fold crests) is above a percentile of the segment's values; folds are the connected components
// of such vertices on the mesh, glued across the periodic cut (the cut's two copies of a wall
// point share their 3D position), small components dropped. Each fold gives its area-weighted
// centroid and the end points of its principal axis (PCA) in flat (u, v) coordinates, plus a
// descriptor (area, orientation, mean curvature) for matching. Eigen in and out.
#include "Registration/SurfaceMap.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::registration {

struct FoldOptions {
  double percentile = 0.90;  // vertices with MeanCurvature above this quantile of the segment
  double minAreaMm2 = 30.0;  // smaller components (noise, partial folds at the ends) are dropped
};

struct FoldFeature {
  Eigen::Vector2d centroid{0, 0};  // flat (u, v), u in [0, period) (periodic meshes)
  Eigen::Vector2d ends[2];         // centroid -/+ half length * axis (half length = sqrt(3 lambda1))
  Eigen::Vector2d axis{1, 0};      // unit principal axis, u component >= 0
  double orientation = 0.0;        // angle of the axis from the u direction, in (-pi/2, pi/2]
  double halfLength = 0.0;         // flat units
  double areaMm2 = 0.0;            // 3D area (mixed vertex areas) of the fold's vertices
  double meanCurvature = 0.0;      // area-weighted mean of MeanCurvature over the fold, mm^-1
  int vertices = 0;
  Eigen::Vector3d position{0, 0, 0};  // 3D position of the centroid (flat -> 3D map), LPS mm
};

// Folds of `flat` (uv, F, position, period) from per-vertex mean curvature H (n values), in a
// deterministic order (by v, then u of the centroid). Throws colonmap::Error when H does not
// have one value per vertex.
std::vector<FoldFeature> DetectFolds(const FlatSegment& flat, const Eigen::VectorXd& H, const FoldOptions& options = {});

// Representative of each vertex after gluing the periodic cut (vertices with identical 3D
// positions get the smallest index among them); glued count in `count` (ids 0..count-1, in
// order of first appearance).
Eigen::VectorXi GlueCutCopies(const Eigen::MatrixXd& position, int& count);

}  // namespace colonmap::registration
