#include "Views/SurfaceTextures.h"

#include "Core/Error.h"

#include <cmath>
#include <map>
#include <utility>

namespace colonmap::views {

TextureTile MakeTextureTile(SurfaceTextureKind kind, const TextureOptions& options, int pixelsPerCell) {
  if (pixelsPerCell < 2 || pixelsPerCell > 1024) throw Error("texture tile: 2..1024 pixels per cell");
  if (options.cellsAcross < 1) throw Error("texture tile: at least one cell across");
  TextureTile t;
  t.cellsPerTile = kind == SurfaceTextureKind::Checkerboard ? 2 : 1;
  const int n = static_cast<int>(t.cellsPerTile) * pixelsPerCell;
  // Flat coordinates of the pixel centres on a rectangle of width 1 (cell size 1 / cellsAcross).
  const double cell = 1.0 / options.cellsAcross;
  Eigen::MatrixXd uv(static_cast<Eigen::Index>(n) * n, 2);
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) uv.row(static_cast<Eigen::Index>(y) * n + x) << (x + 0.5) / pixelsPerCell * cell, (y + 0.5) / pixelsPerCell * cell;
  const Eigen::VectorXd value = kind == SurfaceTextureKind::Checkerboard ? CheckerboardAt(uv, 1.0, options) : CirclesAt(uv, 1.0, options);
  // Tile row y holds texture coordinate t = (y + 0.5) / n (row 0 at t = 0, as VTK reads images).
  t.image = ColourImage(n, n, {0, 0, 0});
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const std::uint8_t g = value(static_cast<Eigen::Index>(y) * n + x) > 0.5 ? 255 : 0;
      t.image.Set(x, y, {g, g, g});
    }
  return t;
}

TexturedMesh TextureCoordinates(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& uv,
                                const Eigen::VectorXd& width, const TextureTile& tile, const TextureOptions& options) {
  const Eigen::Index n = V.rows();
  if (V.cols() != 3 || uv.rows() != n || uv.cols() != 2 || width.size() != n || F.cols() != 3)
    throw Error("surface texture: vertices, flat coordinates and widths differ in size");
  if (options.cellsAcross < 2 || options.cellsAcross % 2 != 0)
    throw Error("surface texture: cellsAcross must be even so that the tile repeats once around");
  if (!(tile.cellsPerTile > 0)) throw Error("surface texture: empty tile");
  if ((F.array() < 0).any() || (F.array() >= n).any()) throw Error("surface texture: a face refers to a missing vertex");
  TexturedMesh out;
  out.F = F;
  std::vector<Eigen::Vector2d> st;
  std::vector<int> source;
  st.reserve(static_cast<std::size_t>(n));
  for (Eigen::Index i = 0; i < n; ++i) {
    if (!(width(i) > 0)) throw Error("surface texture: a vertex has no flat width");
    const double tileSize = width(i) / options.cellsAcross * tile.cellsPerTile;
    st.emplace_back(uv(i, 0) / tileSize, uv(i, 1) / tileSize);
    source.push_back(static_cast<int>(i));
  }
  // Seam faces: corners more than half a period from the first corner in u get copies moved by
  // whole periods (one copy per vertex and shift, shared by the faces that need it).
  std::map<std::pair<int, long>, int> copies;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const int a = F(f, 0);
    for (int k = 1; k < 3; ++k) {
      const int b = F(f, k);
      const double du = uv(b, 0) - uv(a, 0);
      const long shift = std::lround(-du / width(b));
      if (shift == 0) continue;
      auto [it, added] = copies.try_emplace({b, shift}, static_cast<int>(source.size()));
      if (added) {
        const double tileSize = width(b) / options.cellsAcross * tile.cellsPerTile;
        st.emplace_back((uv(b, 0) + shift * width(b)) / tileSize, uv(b, 1) / tileSize);
        source.push_back(b);
      }
      out.F(f, k) = it->second;
    }
  }
  out.V.resize(static_cast<Eigen::Index>(source.size()), 3);
  out.st.resize(static_cast<Eigen::Index>(source.size()), 2);
  out.source.resize(static_cast<Eigen::Index>(source.size()));
  for (std::size_t i = 0; i < source.size(); ++i) {
    out.V.row(static_cast<Eigen::Index>(i)) = V.row(source[i]);
    out.st.row(static_cast<Eigen::Index>(i)) = st[i].transpose();
    out.source(static_cast<Eigen::Index>(i)) = source[i];
  }
  return out;
}

}  // namespace colonmap::views
