#include "Surface/MeanCurvature.h"

#include <Eigen/Geometry>

#include <cmath>
#include <vector>

namespace colonmap::surface {
namespace {

// cot of the angle at a between a->b and a->c; clamped so that degenerate triangles from
// decimation cannot produce infinities.
double Cot(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d u = b - a, v = c - a;
  const double s = u.cross(v).norm();
  const double cot = u.dot(v) / std::max(s, 1e-12 * (u.squaredNorm() + v.squaredNorm()) + 1e-300);
  return std::max(-1e6, std::min(1e6, cot));
}

}  // namespace

Eigen::SparseMatrix<double> CotangentLaplacian(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  std::vector<Eigen::Triplet<double>> t;
  t.reserve(static_cast<std::size_t>(F.rows()) * 12);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    for (int k = 0; k < 3; ++k) {
      // The edge (i, j) opposite corner o.
      const int o = F(f, k), i = F(f, (k + 1) % 3), j = F(f, (k + 2) % 3);
      const double w = Cot(V.row(o).transpose(), V.row(i).transpose(), V.row(j).transpose());
      t.emplace_back(i, j, w);
      t.emplace_back(j, i, w);
      t.emplace_back(i, i, -w);
      t.emplace_back(j, j, -w);
    }
  }
  Eigen::SparseMatrix<double> L(V.rows(), V.rows());
  L.setFromTriplets(t.begin(), t.end());  // sums duplicates in a fixed order: deterministic
  return L;
}

Eigen::VectorXd MixedVertexAreas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::VectorXd A = Eigen::VectorXd::Zero(V.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p[3] = {V.row(F(f, 0)).transpose(), V.row(F(f, 1)).transpose(),
                                  V.row(F(f, 2)).transpose()};
    const double area = 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm();
    int obtuse = -1;
    for (int k = 0; k < 3; ++k)
      if ((p[(k + 1) % 3] - p[k]).dot(p[(k + 2) % 3] - p[k]) < 0) obtuse = k;
    for (int k = 0; k < 3; ++k) {
      if (obtuse >= 0) {
        A(F(f, k)) += obtuse == k ? area / 2 : area / 4;
        continue;
      }
      // Voronoi part at corner k: (|e_kj|^2 cot(angle at l) + |e_kl|^2 cot(angle at j)) / 8.
      const int j = (k + 1) % 3, l = (k + 2) % 3;
      A(F(f, k)) += ((p[j] - p[k]).squaredNorm() * Cot(p[l], p[k], p[j]) +
                     (p[l] - p[k]).squaredNorm() * Cot(p[j], p[k], p[l])) / 8.0;
    }
  }
  return A;
}

Eigen::MatrixXd VertexNormals(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::MatrixXd N = Eigen::MatrixXd::Zero(V.rows(), 3);
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d a = V.row(F(f, 0)), b = V.row(F(f, 1)), c = V.row(F(f, 2));
    const Eigen::RowVector3d n = (b - a).cross(c - a).transpose();  // |n| = 2 area
    for (int k = 0; k < 3; ++k) N.row(F(f, k)) += n;
  }
  for (Eigen::Index i = 0; i < N.rows(); ++i) {
    const double len = N.row(i).norm();
    if (len > 0) N.row(i) /= len;
  }
  return N;
}

Eigen::VectorXd MeanCurvature(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  const Eigen::SparseMatrix<double> L = CotangentLaplacian(V, F);
  const Eigen::MatrixXd LV = L * V;  // row i: sum_j w_ij (v_j - v_i)
  const Eigen::VectorXd A = MixedVertexAreas(V, F);
  const Eigen::MatrixXd N = VertexNormals(V, F);
  Eigen::VectorXd H = Eigen::VectorXd::Zero(V.rows());
  for (Eigen::Index i = 0; i < V.rows(); ++i)
    if (A(i) > 0) H(i) = -LV.row(i).dot(N.row(i)) / (4.0 * A(i));
  return H;
}

}  // namespace colonmap::surface
