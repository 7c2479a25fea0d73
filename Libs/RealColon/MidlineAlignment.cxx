#include "RealColon/MidlineAlignment.h"

#include "Analysis/DynamicTimeWarping.h"
#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"

#include <algorithm>
#include <cmath>

namespace colonmap::realcolon {
namespace {

// Points every ~step along P (both ends kept) and their arc lengths.
Eigen::MatrixXd Resample(const Eigen::MatrixXd& P, double step, Eigen::VectorXd& arcs) {
  const Eigen::VectorXd a = analysis::ArcLength(P);
  const double L = a(a.size() - 1);
  const Eigen::Index n = std::max<Eigen::Index>(2, static_cast<Eigen::Index>(std::ceil(L / step)) + 1);
  Eigen::MatrixXd out(n, 3);
  arcs.resize(n);
  Eigen::Index j = 0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double s = L * static_cast<double>(i) / static_cast<double>(n - 1);
    while (j + 2 < a.size() && a(j + 1) < s) ++j;
    const double d = a(j + 1) - a(j);
    const double t = d > 0 ? std::clamp((s - a(j)) / d, 0.0, 1.0) : 0.0;
    out.row(i) = (1.0 - t) * P.row(j) + t * P.row(j + 1);
    arcs(i) = s;
  }
  return out;
}

}  // namespace

Eigen::VectorXd AlignAlongCurve(const Eigen::MatrixXd& reference, const Eigen::MatrixXd& curve,
                                const Eigen::VectorXd& referenceArcs, double stepMm) {
  if (reference.rows() < 2 || curve.rows() < 2) throw Error("midline alignment: each polyline needs two points");
  Eigen::VectorXd ra, ca;
  const Eigen::MatrixXd R = Resample(reference, stepMm, ra), C = Resample(curve, stepMm, ca);
  const Eigen::Index m = R.rows();
  // Point distance as the cost: the two curves run through the same tube.
  const analysis::Warping w = analysis::WarpSequences(R, C);
  Eigen::VectorXd matched(m);
  const double curveStep = ca(ca.size() - 1) / static_cast<double>(ca.size() - 1);
  for (Eigen::Index k = 0; k < m; ++k) matched(k) = w.matchedInB(k) * curveStep;
  Eigen::VectorXd out(referenceArcs.size());
  for (Eigen::Index q = 0; q < referenceArcs.size(); ++q) {
    const double s = std::clamp(referenceArcs(q), 0.0, ra(m - 1));
    Eigen::Index k = std::min<Eigen::Index>(m - 2, static_cast<Eigen::Index>(s / ra(m - 1) * (m - 1)));
    const double t = std::clamp((s - ra(k)) / (ra(k + 1) - ra(k)), 0.0, 1.0);
    out(q) = (1.0 - t) * matched(k) + t * matched(k + 1);
  }
  return out;
}

}  // namespace colonmap::realcolon
