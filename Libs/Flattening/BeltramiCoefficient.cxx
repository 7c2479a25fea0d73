#include "Flattening/BeltramiCoefficient.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <vector>

namespace colonmap::flattening {

Eigen::VectorXcd BeltramiCoefficient(const Eigen::MatrixXd& V, const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F) {
  Eigen::VectorXcd mu(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    const Eigen::Vector3d n = (p1 - p0).cross(p2 - p0);
    const double len = (p1 - p0).norm();
    if (n.norm() <= 0.0 || len <= 0.0) {
      mu(f) = 0.0;
      continue;
    }
    const Eigen::Vector3d e1 = (p1 - p0) / len, e2 = n.normalized().cross(e1);
    Eigen::Matrix2d P;  // columns: the two edges from corner 0 in the face frame
    P << len, (p2 - p0).dot(e1), 0.0, (p2 - p0).dot(e2);
    Eigen::Matrix2d W;  // columns: the same edges in the plane
    W << uv(F(f, 1), 0) - uv(F(f, 0), 0), uv(F(f, 2), 0) - uv(F(f, 0), 0),
         uv(F(f, 1), 1) - uv(F(f, 0), 1), uv(F(f, 2), 1) - uv(F(f, 0), 1);
    const Eigen::Matrix2d J = W * P.inverse();  // [u_x u_y; v_x v_y]
    const std::complex<double> fz(0.5 * (J(0, 0) + J(1, 1)), 0.5 * (J(1, 0) - J(0, 1)));
    const std::complex<double> fzbar(0.5 * (J(0, 0) - J(1, 1)), 0.5 * (J(1, 0) + J(0, 1)));
    mu(f) = std::abs(fz) > 0.0 ? fzbar / fz : std::complex<double>(1e30, 0.0);
  }
  return mu;
}

Eigen::VectorXd SignedFlatAreas(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F) {
  Eigen::VectorXd a(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector2d q0 = uv.row(F(f, 0)), q1 = uv.row(F(f, 1)), q2 = uv.row(F(f, 2));
    const Eigen::Vector2d d1 = q1 - q0, d2 = q2 - q0;
    a(f) = 0.5 * (d1.x() * d2.y() - d1.y() * d2.x());
  }
  return a;
}

double Quantile(const Eigen::VectorXd& values, double q) {
  if (values.size() == 0) return 0.0;
  std::vector<double> v(values.data(), values.data() + values.size());
  const std::size_t k = std::min(v.size() - 1, static_cast<std::size_t>(std::floor(q * static_cast<double>(v.size() - 1) + 0.5)));
  std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
  return v[k];
}

Eigen::VectorXd SurfaceFaceAreas(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) {
  Eigen::VectorXd area(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const Eigen::Vector3d p0 = V.row(F(f, 0)), p1 = V.row(F(f, 1)), p2 = V.row(F(f, 2));
    area(f) = 0.5 * (p1 - p0).cross(p2 - p0).norm();
  }
  return area;
}

DistortionStats SummarizeDistortion(const Eigen::MatrixXd& V, const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F,
                                    const Eigen::VectorXcd& mu) {
  DistortionStats s;
  s.faces = F.rows();
  if (F.rows() == 0) return s;
  const Eigen::VectorXd flat = SignedFlatAreas(uv, F);
  const Eigen::VectorXd area = SurfaceFaceAreas(V, F);
  s.flipped = static_cast<long>((flat.array() <= 0.0).count());
  const Eigen::VectorXd absMu = mu.cwiseAbs();
  s.muMean = absMu.mean();
  s.muP99 = Quantile(absMu, 0.99);
  s.muMax = absMu.maxCoeff();
  const double totalFlat = flat.sum(), total = area.sum();
  Eigen::VectorXd ratio(F.rows());
  for (Eigen::Index f = 0; f < F.rows(); ++f)
    ratio(f) = area(f) > 0 ? (flat(f) / totalFlat) / (area(f) / total) : 0.0;
  s.areaRatioMin = ratio.minCoeff();
  s.areaRatioMax = ratio.maxCoeff();
  s.areaRatioP01 = Quantile(ratio, 0.01);
  s.areaRatioMedian = Quantile(ratio, 0.5);
  s.areaRatioP99 = Quantile(ratio, 0.99);
  double m = 0.0, m2 = 0.0;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    if (ratio(f) <= 0) continue;
    const double l = std::log(ratio(f)), w = area(f) / total;
    m += w * l;
    m2 += w * l * l;
  }
  s.logAreaRatioStd = std::sqrt(std::max(0.0, m2 - m * m));
  return s;
}

}  // namespace colonmap::flattening
