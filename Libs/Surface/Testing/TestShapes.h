#pragma once
// Known shapes for the surface tests (Eigen only): an icosphere, a torus and an open cylinder,
// each with right-hand (counter-clockwise seen from outside) faces.
#include <Core/TriangleMesh.h>

namespace colonmap::surface::testing {

// Icosahedron subdivided `levels` times, vertices projected onto the sphere of radius r.
TriangleMesh Icosphere(double r, int levels);
// Torus with radii R (tube centre) and a (tube), n x m grid (around the axis x around the tube).
TriangleMesh Torus(double R, double a, int n, int m);
// Open cylinder of radius r and length h along z, n around, m rings (closed=false ends).
TriangleMesh OpenCylinder(double r, double h, int n, int m);

}  // namespace colonmap::surface::testing
