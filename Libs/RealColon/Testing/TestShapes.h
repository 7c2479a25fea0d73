#pragma once
// Known shapes for the real-colon tests.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

namespace colonmap::realcolon::testing {

// Open cylinder of radius r along z from 0 to h: n around, m + 1 rings; faces counter-clockwise
// seen from inside (normals into the lumen, DESIGN 3.3).
TriangleMesh Cylinder(double r, double h, int n, int m);

// Closed surface of the points within `radius` of a polyline (a tube with round ends), contoured
// on a `grid` mm lattice (vtkFlyingEdges3D), normals into the tube.
TriangleMesh TubeAround(const Eigen::MatrixXd& polyline, double radius, double grid);
// The same with a radius per polyline point (linear along each segment).
TriangleMesh TubeAround(const Eigen::MatrixXd& polyline, const Eigen::VectorXd& radii, double grid);

// Distance from p to the polyline and the arc length of its nearest point.
double NearestArc(const Eigen::MatrixXd& polyline, const Eigen::Vector3d& p, double* distance = nullptr);

}  // namespace colonmap::realcolon::testing
