#pragma once
// One harmonic along-colon function on the closed colon surface (issue 19), libigl style.
//
// f = 0 on a geodesic disc around one tip of the tube and 1 on a disc around the other; the
// intrinsic Delaunay cotangent Laplacian with its few negative weights raised
// (Flattening/IntrinsicDelaunay.h), so the discrete maximum principle holds and f has no
// interior extremum. Between the discs the surface is a topological annulus on which f has no
// interior critical point: each level set {f = c} is one loop around the colon, and loops of
// different levels never meet, however the colon bends or touches itself. So cuts made at level
// sets of f are disjoint closed loops by construction (ColonSegments.h).
#include "Landmarks/MeshGraph.h"

#include <Eigen/Core>
#include <vector>

namespace colonmap::landmarks {

// The vertices within edge-path distance radiusMm of vertex `centre` (sorted).
std::vector<int> GeodesicDisc(const EdgeGraph& graph, int centre, double radiusMm);

// V, F: a closed, connected surface. zero, one: disjoint non-empty vertex sets (the two ends).
// Returns f per vertex: 0 on `zero`, 1 on `one`, harmonic elsewhere (in [0, 1] up to rounding).
// Throws colonmap::Error when the sets are empty or overlap.
Eigen::VectorXd AlongColonFunction(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const std::vector<int>& zero,
                                   const std::vector<int>& one);

// The same between discs of radius discMm around the tip vertices `first` (f = 0) and `second`.
Eigen::VectorXd AlongColonFunction(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, int first, int second,
                                   double discMm);

}  // namespace colonmap::landmarks
