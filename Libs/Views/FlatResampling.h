#pragma once
// Pictures of the flat domain through a registration (issue 8, paper Fig. 13): the pixels of a
// grid over one scan's flat rectangle are located in that scan's flat mesh, and the map stored
// per vertex (registration.vtp: ProneFlatUV per supine vertex) is interpolated there, giving
// each pixel's image in the other scan's flat coordinates; the other scan's curvature image is
// then sampled at those places. So the resampled prone picture shows, at supine (u, v), the
// prone anatomy the registration puts there. Eigen and Core in and out.
#include "Core/Cancel.h"
#include "Core/Volume.h"

#include <Eigen/Core>

namespace colonmap::views {

// A pixel grid over the flat rectangle [0, width] x [0, height] (flat units): pixel (i, j)
// centred at ((i + 0.5) width / nx, (j + 0.5) height / ny); j = 0 is the v = 0 (anal) end.
// Pixel p = j * nx + i in the per-pixel arrays below.
struct FlatGrid {
  int nx = 1, ny = 1;
  double width = 1.0, height = 1.0;
  Eigen::Vector2d Centre(int i, int j) const { return {(i + 0.5) * width / nx, (j + 0.5) * height / ny}; }
  Eigen::MatrixXd Centres() const;  // (nx ny) x 2, the identity map of the grid
};

// The grid of a flat rectangle at `pixelsPerUnit` pixels per flat unit (at least 1 x 1).
FlatGrid GridFor(double width, double height, double pixelsPerUnit);

// Which face of the flat mesh (uv: n x 2, F: m x 3, u periodic with `period` > 0, or 0 for none)
// holds each pixel centre, and where. face = -1 where the centre lies more than `tolerance`
// flat units from every face (outside the domain); nearer ones get the nearest face, clamped.
struct FlatPixelHits {
  Eigen::VectorXi face;  // nx ny
  Eigen::MatrixXd bary;  // nx ny x 3
};
FlatPixelHits LocatePixels(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, double period, const FlatGrid& grid,
                           double tolerance, ProgressSink& progress);

// Per pixel: barycentric interpolation in the pixel's face of per-vertex target coordinates
// (n x 2: the map's image of each vertex in the target's flat coordinates). When the target is
// periodic in u (targetPeriod > 0), the three corners' u are first brought within half a period
// of the first corner's, so a face whose image straddles the target's cut interpolates across
// the cut and not the long way round. NaN rows where the pixel has no face.
Eigen::MatrixXd MapPixels(const FlatPixelHits& hits, const Eigen::MatrixXi& F, const Eigen::MatrixXd& targetUV,
                          double targetPeriod);

// Per pixel: the value of its face (per-face values, e.g. dilatation K); NaN where no face.
Eigen::VectorXd FaceValuesAtPixels(const FlatPixelHits& hits, const Eigen::VectorXd& faceValues);

// Bilinear samples of a flat image at flat coordinates uv (rows; NaN rows give NaN). The image
// is what ColonFlattening writes (curvature_X.nrrd): nx x ny x 1, in mm, pixel (i, j) centred at
// origin + (i sx, j sy), covering [0, nx sx] x [0, ny sy]. A flat coordinate is scaled by
// `unitsToMm` (mm per flat unit) to reach the image. periodicU: u wraps around the image width
// (a periodic-cut flattening); otherwise u, like v, is clamped to the image. v outside
// [0, ny sy] by more than half a pixel gives NaN (beyond the segment's ends).
Eigen::VectorXf SampleFlatImage(const Volume<float>& image, const Eigen::MatrixXd& uv, double unitsToMm, bool periodicU);

// Per-pixel values (p = j nx + i) as a picture matrix: ny x nx, row 0 = top = largest v.
Eigen::MatrixXf PixelsToPicture(const Eigen::VectorXf& values, const FlatGrid& grid);

}  // namespace colonmap::views
