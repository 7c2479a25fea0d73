#pragma once
// A map between two triangulated surfaces stored the way registration.vtp keeps it (DESIGN §3.3):
// per source vertex, the target triangle holding its image and barycentric coordinates there.
// Built by locating flat query points in the target's flat mesh (FlatLocator), and measured per
// source face by the Beltrami coefficient of the piecewise-affine 3D -> 3D map. Eigen in and out.
#include "Core/Cancel.h"

#include <Eigen/Core>

#include <complex>

namespace colonmap::registration {

// A flattened segment: flat positions, faces, 3D positions (same vertex order) and the period of
// u (0: not periodic).
struct FlatSegment {
  Eigen::MatrixXd uv;        // n x 2
  Eigen::MatrixXi F;         // m x 3
  Eigen::MatrixXd position;  // n x 3, LPS mm
  double period = 0.0;
};

struct VertexImages {
  Eigen::VectorXi face;      // n_query: target face index
  Eigen::MatrixXd bary;      // n_query x 3
  Eigen::MatrixXd uv;        // n_query x 2: image in the target's flat coordinates
  Eigen::MatrixXd position;  // n_query x 3: image on the target surface (barycentric combination)
  long outside = 0;          // queries outside every target face (clamped to the nearest)
  double maxOutsideDistance = 0.0;  // largest flat distance of those
};

// Images of the flat points `queries` (n x 2) in `target`. progress: Report(0..1), may throw Cancelled.
VertexImages LocateInTarget(const Eigen::MatrixXd& queries, const FlatSegment& target, ProgressSink& progress);

// Barycentric interpolation of per-vertex values (n_target x k) of `F` at the images.
Eigen::MatrixXd Interpolate(const VertexImages& images, const Eigen::MatrixXi& F, const Eigen::MatrixXd& values);

// Beltrami coefficient per face of the piecewise-affine map that sends source triangle
// (V.row(F(f,0)), ...) onto (image.row(F(f,0)), ...), each triangle in its own plane (frames as in
// Flattening/BeltramiCoefficient.h; the image frame's normal is the image triangle's own normal).
// |mu| < 1 orientation preserving; K = (1 + |mu|) / (1 - |mu|).
Eigen::VectorXcd SurfaceMapBeltrami(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& image);

// The same map's Beltrami coefficient with the source frame of the flat domain: uv (n x 2) are the
// source vertices' flat coordinates (u around the colon, v along it), the same frame for every
// face, so that arg(mu) / 2 is the stretch direction measured from the u axis (DESIGN §2.4: the
// angle theta); in each triangle's own frame, as SurfaceMapBeltrami does, arg(mu) depends on
// the order of the triangle's corners. |mu| is that of the map from the flat domain (equal to
// SurfaceMapBeltrami's up to the conformal distortion of the flattening). Faces whose flat image
// is degenerate or reversed keep SurfaceMapBeltrami's value.
Eigen::VectorXcd FlatFrameBeltrami(const Eigen::MatrixXd& V, const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F,
                                   const Eigen::MatrixXd& image);

// Dilatation K per face from mu (+inf for |mu| >= 1).
Eigen::VectorXd Dilatation(const Eigen::VectorXcd& mu);

}  // namespace colonmap::registration
