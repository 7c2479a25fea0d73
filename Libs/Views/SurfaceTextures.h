#pragma once
// The checkerboard and circle textures of DistortionTextures.h as image textures on a 3D surface
// (issue 8, paper Figs. 11-12): a repeating tile sampled from the same definitions
// (CheckerboardAt, CirclesAt), and per-vertex texture coordinates from flat (u, v), so that the
// renderer's texture lookup shows at each surface point exactly the value the flat pictures show
// at its flat coordinates, with sharp edges whatever the mesh resolution.
//
// The flat u is periodic (once around the colon). A face whose corners' u lie on both sides of
// the period's seam (the prone surface's images in the supine rectangle cross it) would
// interpolate across the whole rectangle: such faces get their own copies of the corners, moved
// by whole periods next to the face's first corner. A period holds an even number of cells, so
// a move by one period is a move by whole tiles and the texture is unchanged. Eigen in and out.
#include "Views/ColourMap.h"
#include "Views/DistortionTextures.h"

#include <Eigen/Core>

namespace colonmap::views {

enum class SurfaceTextureKind { Checkerboard, Circles };

struct TextureTile {
  ColourImage image;       // square tile, grey: 0 black, 1 white (as the flat pictures' grey map)
  double cellsPerTile = 1; // texture coordinate 1 = this many cells of the flat texture
};

// The tile of `kind`: 2 x 2 cells for the checkerboard, one cell for the circles, `pixelsPerCell`
// pixels per cell (>= 2), sampled at pixel centres from CheckerboardAt / CirclesAt.
TextureTile MakeTextureTile(SurfaceTextureKind kind, const TextureOptions& options = {}, int pixelsPerCell = 32);

// A mesh with texture coordinates; `source` maps each vertex to the input vertex it copies.
struct TexturedMesh {
  Eigen::MatrixXd V;       // n x 3
  Eigen::MatrixXi F;       // m x 3 (same faces, same order as the input)
  Eigen::MatrixXd st;      // n x 2 texture coordinates (tile units)
  Eigen::VectorXi source;  // n: input vertex of each vertex
};

// Texture coordinates st = (u, v) / (cell size * tile.cellsPerTile) with cell size =
// width(vertex) / options.cellsAcross, width per vertex (the flat width of its segment), and the
// seam faces split as described above. Throws colonmap::Error for sizes that disagree, a width
// <= 0 or an odd options.cellsAcross (the tile would not repeat once around).
TexturedMesh TextureCoordinates(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& uv,
                                const Eigen::VectorXd& width, const TextureTile& tile, const TextureOptions& options = {});

}  // namespace colonmap::views
