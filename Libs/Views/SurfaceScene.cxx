#include "Views/SurfaceScene.h"

#include "Core/Error.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>

namespace colonmap::views {

Eigen::MatrixXd VertexNormals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  if ((F.array() < 0).any() || (F.array() >= V.rows()).any()) throw Error("surface: a face refers to a missing vertex");
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();  // length = twice the area
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const double l = N.row(i).norm();
    if (l > 0 && std::isfinite(l)) N.row(i) /= l;
    else N.row(i) << 0, 0, 1;
  }
  return N;
}

SurfaceScene ColouredSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::VectorXd& faceValues, double low,
                             double high, ColourMapKind kind, const Bgr& nanColour) {
  if (faceValues.size() != F.rows()) throw Error("surface colours: one value per face is needed");
  SurfaceScene s;
  s.V = V;
  s.F = F;
  s.normals = VertexNormals(V, F);
  // ColourOf quantises to 256 levels; it builds OpenCV's table on every call, so look the
  // levels up once (the same rounding as ColourOf: level = round(255 t)).
  std::array<Bgr, 256> table;
  for (int k = 0; k < 256; ++k) table[static_cast<std::size_t>(k)] = ColourOf(low + (high - low) * (k / 255.0), low, high, kind, nanColour);
  s.faceColours.reserve(static_cast<std::size_t>(F.rows()));
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const double v = faceValues(f);
    if (!std::isfinite(v)) {  // as ColourOf: NaN and infinite values (K of a degenerate face)
      s.faceColours.push_back(nanColour);
      continue;
    }
    const double t = high > low ? (v - low) / (high - low) : 0.0;
    s.faceColours.push_back(table[static_cast<std::size_t>(std::lround(255.0 * std::clamp(t, 0.0, 1.0)))]);
  }
  return s;
}

SurfaceScene TexturedSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& uv, const Eigen::VectorXd& width,
                             SurfaceTextureKind kind, const TextureOptions& options) {
  const TextureTile tile = MakeTextureTile(kind, options);
  const TexturedMesh t = TextureCoordinates(V, F, uv, width, tile, options);
  // Normals of the original mesh, so the seam copies shade like their originals.
  const Eigen::MatrixXd N = VertexNormals(V, F);
  SurfaceScene s;
  s.V = t.V;
  s.F = t.F;
  s.normals.resize(t.V.rows(), 3);
  for (Eigen::Index i = 0; i < t.V.rows(); ++i) s.normals.row(i) = N.row(t.source(i));
  s.st = t.st;
  s.texture = tile.image;
  return s;
}

}  // namespace colonmap::views
