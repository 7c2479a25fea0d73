#pragma once
// What SurfaceRenderer draws (issue 8, paper Figs. 11-12): one triangle mesh with smooth vertex
// normals, coloured either per face (a scalar field through a colour map, e.g. the dilatation K
// or the angle theta: the same colours as the flat pictures and their colour bars) or by a
// texture tile at per-vertex texture coordinates (the checkerboard / circles carried across).
// Eigen and ColourImage only.
#include "Views/ColourMap.h"
#include "Views/SurfaceTextures.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::views {

struct SurfaceScene {
  Eigen::MatrixXd V;            // n x 3, mm (LPS)
  Eigen::MatrixXi F;            // m x 3
  Eigen::MatrixXd normals;      // n x 3 unit vertex normals (for shading; either orientation)
  std::vector<Bgr> faceColours; // m colours, or empty when textured
  Eigen::MatrixXd st;           // n x 2 texture coordinates when textured, else empty
  ColourImage texture;          // the repeating tile when textured
};

// Area-weighted vertex normals (sum of the faces' cross products, normalised; a vertex in no
// face, or only in degenerate ones, gets (0, 0, 1)).
Eigen::MatrixXd VertexNormals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Faces coloured by `faceValues` (m) through the map from `low` to `high` (ColourOf: the colour
// the flat pictures and ColourBar give the same value); NaN and infinite faces get `nanColour`.
SurfaceScene ColouredSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& faceValues, double low,
                             double high, ColourMapKind kind, const Bgr& nanColour = {200, 200, 200});

// The surface textured by `kind` at flat coordinates `uv` (n x 2) on rectangles of width
// `width` (per vertex), see SurfaceTextures.h.
SurfaceScene TexturedSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& uv, const Eigen::VectorXd& width,
                             SurfaceTextureKind kind, const TextureOptions& options = {});

}  // namespace colonmap::views
