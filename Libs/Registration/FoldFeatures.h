#pragma once
// Haustral fold features of one flattened colon segment (DESIGN §2.4, issue 7): folds are the
// ridges of high mean curvature (MeanCurvature is positive on fold crests).
//   GraphCut (default): the segment's mean-curvature image (`pixelsAround` pixels around, square
//     pixels in flat units) is labelled fold / background by a graph cut (FoldGraphCut.h: data
//     term from the normalised curvature, smoothness between neighbouring pixels, periodic
//     around); folds are the 4-connected components of fold pixels (glued around), components
//     under minAreaMm2 dropped.
//   Threshold (the former method, kept for comparison): vertices above a percentile of the
//     segment's MeanCurvature, connected components on the mesh glued across the periodic cut.
// Each fold gives its area-weighted centroid and the end points of its principal axis (PCA) in
// flat (u, v) coordinates, and a descriptor for matching: area, orientation, half length, mean
// curvature, a curvature profile along the axis, and its distance from the nearest taenia line
// (the columns where folds are interrupted, see TaeniaColumns). Eigen in and out.
#include "Registration/SurfaceMap.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::registration {

enum class FoldDetection { GraphCut, Threshold };

struct FoldOptions {
  FoldDetection method = FoldDetection::GraphCut;
  double percentile = 0.90;  // Threshold: vertices with MeanCurvature above this quantile
  double minAreaMm2 = 30.0;  // smaller components (noise, partial folds at the ends) are dropped
  int pixelsAround = 96;     // GraphCut: image columns over the width (about 1.7 mm on the colon)
  double quantile = 0.88;    // GraphCut: data-term threshold (FoldGraphCut.h)
  double smoothness = 0.5;   // GraphCut: pairwise cost
};

constexpr int kProfileSamples = 9;

struct FoldFeature {
  Eigen::Vector2d centroid{0, 0};  // flat (u, v), u in [0, period) (periodic meshes)
  Eigen::Vector2d ends[2];         // centroid -/+ half length * axis (half length = sqrt(3 lambda1))
  Eigen::Vector2d axis{1, 0};      // unit principal axis, u component >= 0
  double orientation = 0.0;        // angle of the axis from the u direction, in (-pi/2, pi/2]
  double halfLength = 0.0;         // flat units
  double areaMm2 = 0.0;            // 3D area (mixed vertex areas) of the fold's vertices
  double meanCurvature = 0.0;      // area-weighted mean of MeanCurvature over the fold, mm^-1
  int vertices = 0;                // mesh vertices (Threshold) or pixels (GraphCut)
  Eigen::Vector3d position{0, 0, 0};  // 3D position of the centroid (flat -> 3D map), LPS mm
  // Normalised curvature at kProfileSamples points from ends[0] to ends[1] (GraphCut; zeros else).
  Eigen::Matrix<double, kProfileSamples, 1> profile = Eigen::Matrix<double, kProfileSamples, 1>::Zero();
  double taeniaDistance = 0.5;     // flat distance of the nearer axis end from a taenia line
};

// Three taenia lines u = phase + k period / 3 (k = 0, 1, 2) of a fold mask (rows x cols,
// row-major, periodic): the phase minimising the fold occupancy of the three columns (taeniae
// interrupt the folds). In flat units of u.
double TaeniaPhase(const std::vector<unsigned char>& fold, int rows, int cols, double period);

// Folds of `flat` (uv, F, position, period) from per-vertex mean curvature H (n values), in a
// deterministic order (by v, then u of the centroid). Throws colonmap::Error when H does not
// have one value per vertex.
std::vector<FoldFeature> DetectFolds(const FlatSegment& flat, const Eigen::VectorXd& H, const FoldOptions& options = {});

// Representative of each vertex after gluing the periodic cut (vertices with identical 3D
// positions get the smallest index among them); glued count in `count` (ids 0..count-1, in
// order of first appearance).
Eigen::VectorXi GlueCutCopies(const Eigen::MatrixXd& position, int& count);

}  // namespace colonmap::registration
