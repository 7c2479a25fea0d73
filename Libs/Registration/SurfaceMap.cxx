#include "Registration/SurfaceMap.h"

#include "Flattening/BeltramiCoefficient.h"
#include "Registration/FlatLocator.h"

#include <Eigen/Geometry>
#include <chrono>
#include <complex>
#include <limits>

namespace colonmap::registration {

VertexImages LocateInTarget(const Eigen::MatrixXd& queries, const FlatSegment& target, ProgressSink& progress) {
  const FlatTriangleLocator locator(target.uv, target.F, target.period);
  VertexImages r;
  const Eigen::Index n = queries.rows();
  r.face.resize(n);
  r.bary.resize(n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    if ((i & 4095) == 0) progress.Report(static_cast<double>(i) / std::max<Eigen::Index>(n, 1));
    const FlatHit h = locator.Locate(Eigen::Vector2d(queries(i, 0), queries(i, 1)));
    r.face(i) = h.face;
    r.bary.row(i) = h.bary.transpose();
    if (!h.inside) {
      ++r.outside;
      r.maxOutsideDistance = std::max(r.maxOutsideDistance, h.distance);
    }
  }
  r.uv = Interpolate(r, target.F, target.uv);
  r.position = Interpolate(r, target.F, target.position);
  progress.Report(1.0);
  return r;
}

Eigen::MatrixXd Interpolate(const VertexImages& images, const Eigen::MatrixXi& F, const Eigen::MatrixXd& values) {
  Eigen::MatrixXd out(images.face.size(), values.cols());
  for (Eigen::Index i = 0; i < images.face.size(); ++i) {
    const int f = images.face(i);
    out.row(i) = images.bary(i, 0) * values.row(F(f, 0)) + images.bary(i, 1) * values.row(F(f, 1)) +
                 images.bary(i, 2) * values.row(F(f, 2));
  }
  return out;
}

Eigen::VectorXcd SurfaceMapBeltrami(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& image) {
  // Unshared copies of each face: source corners in 3D, image corners in the image triangle's
  // own orthonormal frame (e1 along its first edge, e2 = n x e1), so that the flat Beltrami
  // coefficient of Flattening applies unchanged.
  const Eigen::Index m = F.rows();
  Eigen::MatrixXd Vs(3 * m, 3), uv(3 * m, 2);
  Eigen::MatrixXi Fs(m, 3);
  for (Eigen::Index f = 0; f < m; ++f) {
    const Eigen::Vector3d a = image.row(F(f, 0)), b = image.row(F(f, 1)), c = image.row(F(f, 2));
    Eigen::Vector3d e1 = b - a, n = (b - a).cross(c - a);
    if (e1.norm() > 0) e1.normalize();
    if (n.norm() > 0) n.normalize();
    const Eigen::Vector3d e2 = n.cross(e1);
    for (int k = 0; k < 3; ++k) {
      Vs.row(3 * f + k) = V.row(F(f, k));
      const Eigen::Vector3d d = image.row(F(f, k)).transpose() - a;
      uv(3 * f + k, 0) = d.dot(e1);
      uv(3 * f + k, 1) = d.dot(e2);
      Fs(f, k) = static_cast<int>(3 * f + k);
    }
  }
  return flattening::BeltramiCoefficient(Vs, uv, Fs);
}

Eigen::VectorXcd FlatFrameBeltrami(const Eigen::MatrixXd& V, const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F,
                                   const Eigen::MatrixXd& image) {
  Eigen::VectorXcd mu = SurfaceMapBeltrami(V, F, image);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d p0 = uv.row(F(f, 0)), p1 = uv.row(F(f, 1)), p2 = uv.row(F(f, 2));
    Eigen::Matrix2d S;  // source edges in the global (u, v) frame
    S.col(0) = p1 - p0;
    S.col(1) = p2 - p0;
    if (S.determinant() <= 1e-14) continue;
    // Image edges in the image triangle's own frame: a rotation of the image leaves mu unchanged.
    const Eigen::Vector3d a = image.row(F(f, 0)), b = image.row(F(f, 1)), c = image.row(F(f, 2));
    Eigen::Vector3d e1 = b - a;
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (e1.norm() == 0.0 || n.norm() == 0.0) continue;
    e1.normalize();
    const Eigen::Vector3d e2 = n.normalized().cross(e1);
    Eigen::Matrix2d T;
    T << (b - a).dot(e1), (c - a).dot(e1), (b - a).dot(e2), (c - a).dot(e2);
    const Eigen::Matrix2d J = T * S.inverse();
    const std::complex<double> fz(0.5 * (J(0, 0) + J(1, 1)), 0.5 * (J(1, 0) - J(0, 1)));
    const std::complex<double> fzbar(0.5 * (J(0, 0) - J(1, 1)), 0.5 * (J(1, 0) + J(0, 1)));
    if (std::abs(fz) > 0.0) mu(f) = fzbar / fz;
  }
  return mu;
}

Eigen::VectorXd Dilatation(const Eigen::VectorXcd& mu) {
  Eigen::VectorXd K(mu.size());
  for (Eigen::Index f = 0; f < mu.size(); ++f) {
    const double a = std::abs(mu(f));
    K(f) = a < 1.0 ? (1.0 + a) / (1.0 - a) : std::numeric_limits<double>::infinity();
  }
  return K;
}

}  // namespace colonmap::registration
