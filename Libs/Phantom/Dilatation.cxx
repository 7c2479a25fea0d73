#include "Dilatation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace colonmap {
namespace phantom {
namespace {

// Edge vectors of a triangle in an orthonormal basis of its plane (columns e1, e2).
bool PlanarEdges(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c, Eigen::Matrix2d& E) {
  const Eigen::Vector3d e1 = b - a, e2 = c - a;
  const double l1 = e1.norm();
  const Eigen::Vector3d n = e1.cross(e2);
  if (l1 <= 0.0 || n.norm() <= 1e-14 * l1 * e2.norm()) return false;
  const Eigen::Vector3d x = e1 / l1, y = n.cross(e1).normalized();
  E << l1, e2.dot(x), 0.0, e2.dot(y);
  return true;
}

DilatationSummary Summarize(std::vector<double> v) {
  DilatationSummary s;
  s.count = v.size();
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  double sum = 0.0;
  for (double x : v) sum += x;
  s.mean = sum / v.size();
  auto quantile = [&](double q) {
    const double pos = q * (v.size() - 1);
    const std::size_t i = static_cast<std::size_t>(pos);
    const double t = pos - i;
    return i + 1 < v.size() ? (1 - t) * v[i] + t * v[i + 1] : v[i];
  };
  s.median = quantile(0.5);
  s.p90 = quantile(0.9);
  s.max = v.back();
  return s;
}

}  // namespace

Eigen::VectorXd FaceDilatation(const TriangleMesh& from, const TriangleMesh& to) {
  if (from.F.rows() != to.F.rows() || from.F.cols() != 3 || to.F.cols() != 3 || from.F != to.F)
    throw std::invalid_argument("FaceDilatation: meshes must share their faces");
  Eigen::VectorXd K(from.F.rows());
  for (Eigen::Index f = 0; f < from.F.rows(); ++f) {
    Eigen::Matrix2d P, Q;
    const int a = from.F(f, 0), b = from.F(f, 1), c = from.F(f, 2);
    const bool ok = PlanarEdges(from.V.row(a).transpose(), from.V.row(b).transpose(), from.V.row(c).transpose(), P) &&
                    PlanarEdges(to.V.row(a).transpose(), to.V.row(b).transpose(), to.V.row(c).transpose(), Q);
    if (!ok) {
      K[f] = std::numeric_limits<double>::infinity();
      continue;
    }
    // Affine map J = Q P^-1; its singular values in closed form.
    const Eigen::Matrix2d J = Q * P.inverse();
    const double E = J.squaredNorm(), det = std::fabs(J.determinant());
    const double disc = std::sqrt(std::max(0.0, E * E - 4.0 * det * det));
    const double s1 = std::sqrt(0.5 * (E + disc)), s2sq = 0.5 * (E - disc);
    // s2 from det / s1 is accurate when the two are nearly equal (K ~ 1).
    const double s2 = s1 > 0 ? det / s1 : std::sqrt(std::max(0.0, s2sq));
    K[f] = s2 > 0 ? std::max(1.0, s1 / s2) : std::numeric_limits<double>::infinity();
  }
  return K;
}

Eigen::VectorXi FaceSegments(const TriangleMesh& mesh) {
  Eigen::VectorXi seg = Eigen::VectorXi::Constant(mesh.F.rows(), -1);
  const auto it = mesh.pointData.find("SegmentId");
  if (it == mesh.pointData.end()) return seg;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) seg[f] = static_cast<int>(std::lround(it->second.values(mesh.F(f, 0), 0)));
  return seg;
}

DilatationStats SummarizeDilatation(const Eigen::VectorXd& K, const Eigen::VectorXi& faceSegment) {
  DilatationStats stats;
  std::vector<double> all(K.data(), K.data() + K.size());
  std::array<std::vector<double>, 5> per;
  for (Eigen::Index f = 0; f < K.size() && f < faceSegment.size(); ++f)
    if (faceSegment[f] >= 0 && faceSegment[f] < 5) per[faceSegment[f]].push_back(K[f]);
  for (int k = 0; k < 5; ++k) stats.segment[k] = Summarize(per[k]);
  stats.all = Summarize(all);
  return stats;
}

}  // namespace phantom
}  // namespace colonmap
