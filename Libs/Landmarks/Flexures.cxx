#include "Flexures.h"

#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace colonmap::landmarks {

const std::array<const char*, 4>& Flexures::Names() {
  static const std::array<const char*, 4> names{"HF", "SF", "DSJ", "RSJ"};
  return names;
}

Eigen::VectorXd BendAngles(const Eigen::MatrixXd& P, int w) {
  const Eigen::Index n = P.rows();
  Eigen::VectorXd out = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Eigen::RowVector3d u = P.row(i) - P.row(std::max<Eigen::Index>(i - w, 0));
    const Eigen::RowVector3d v = P.row(std::min<Eigen::Index>(i + w, n - 1)) - P.row(i);
    if (u.norm() < 1e-9 || v.norm() < 1e-9) continue;
    out(i) = std::acos(std::clamp(u.dot(v) / (u.norm() * v.norm()), -1.0, 1.0)) * 180.0 / M_PI;
  }
  return out;
}

namespace {

int SharpestNear(const Eigen::VectorXd& bend, int i, int r) {
  const int n = static_cast<int>(bend.size());
  int best = i;
  for (int j = std::max(0, i - r); j <= std::min(n - 1, i + r); ++j)
    if (bend(j) > bend(best)) best = j;
  return best;
}

std::string Mm(double v) {
  std::ostringstream s;
  s.precision(0);
  s << std::fixed << v << " mm";
  return s.str();
}

}  // namespace

Flexures FindFlexures(const Eigen::MatrixXd& P, const Eigen::VectorXd& arc, const FlexureOptions& o) {
  const int n = static_cast<int>(P.rows());
  if (n < 10) throw Error("centreline too short to find flexures");
  const double L = arc(n - 1);
  const double step = L / (n - 1);
  const Eigen::VectorXd bend = BendAngles(P, std::max(1, static_cast<int>(std::round(o.bendScaleMm / step))));
  const int refine = std::max(1, static_cast<int>(std::round(o.refineMm / step)));
  const double xmid = 0.5 * (P.col(0).minCoeff() + P.col(0).maxCoeff());

  std::string found;
  const auto fail = [&](const std::string& what) {
    throw Error("cannot find the four flexures: " + what + (found.empty() ? "" : " (found " + found + ")") +
                "; centreline " + Mm(L));
  };
  int sf = -1;
  for (int i = 0; i < n; ++i)
    if (P(i, 0) > xmid && (sf < 0 || P(i, 2) > P(sf, 2))) sf = i;
  if (sf < 0) fail("no centreline point on the left side for the splenic flexure");
  sf = SharpestNear(bend, sf, refine);
  found += "SF at " + Mm(arc(sf));
  int hf = -1;
  for (int i = sf + 1; i < n; ++i)
    if (P(i, 0) < xmid && (hf < 0 || P(i, 2) > P(hf, 2))) hf = i;
  if (hf < 0) fail("no centreline point on the right side between the splenic flexure and the cecum");
  hf = SharpestNear(bend, hf, refine);
  if (hf <= sf) fail("the hepatic flexure is not on the cecum side of the splenic flexure");
  found += ", HF at " + Mm(arc(hf));

  const int w = std::max(1, static_cast<int>(std::round(o.tangentMm / step)));
  // First sample from `i` walking in `dir` where the direction of travel (over +-w samples)
  // leaves `ref` by more than the threshold; -1 if none before `stop`.
  const auto leave = [&](int i, int dir, const Eigen::RowVector3d& ref, int stop, double deg) {
    const double cosMax = std::cos(deg * M_PI / 180.0);
    for (; i != stop && i >= 0 && i < n; i += dir) {
      const Eigen::RowVector3d t = P.row(std::clamp(i + dir * w, 0, n - 1)) - P.row(std::clamp(i - dir * w, 0, n - 1));
      if (t.norm() > 0 && t.dot(ref) / t.norm() < cosMax) return i;
    }
    return -1;
  };
  const Eigen::RowVector3d up(0, 0, 1);
  // HF: the ascending colon rises from the cecum; it ends where the colon turns away from +z.
  const int hfv = leave(n - 1 - static_cast<int>(std::round(o.cecumSkipMm / step)), -1, up, sf, o.hepaticExitDeg);
  if (hfv < 0) fail("the ascending colon does not turn between the cecum and the splenic flexure");
  found += ", HF at " + Mm(arc(hfv)) + " (highest right " + Mm(arc(hf)) + ")";
  hf = hfv;
  // DSJ: the descending colon falls from SF; it ends where the colon turns away from -z.
  const int dsj = leave(sf - static_cast<int>(std::round(o.splenicBendMm / step)), -1, -up, 0, o.descendingExitDeg);
  if (dsj < 0) fail("no end of the descending colon below the splenic flexure");
  found += ", DSJ at " + Mm(arc(dsj));
  // RSJ: the rectum rises from the anus; it ends where the colon turns away from +z. The anal
  // canal itself leans (40-55 degrees on the phantom), so the walk starts at the rectum's most
  // vertical point within rectumSearchMm of the anal end, not at a fixed distance.
  int vertical = static_cast<int>(std::round(o.minRectumMm / step));
  double bestCos = -2.0;
  for (int i = 0; i < n && arc(i) <= o.rectumSearchMm && i < dsj; ++i) {
    const Eigen::RowVector3d t = P.row(std::min(i + w, n - 1)) - P.row(std::max(i - w, 0));
    const double c = t.norm() > 0 ? t.dot(up) / t.norm() : -2.0;
    if (c > bestCos) { bestCos = c; vertical = i; }
  }
  const int rsj = leave(vertical, +1, up, dsj, o.rectumExitDeg);
  if (rsj < 0) fail("the rectum does not turn below the descending-sigmoid junction");

  Flexures f;
  const int idx[4] = {hf, sf, dsj, rsj};
  for (int k = 0; k < 4; ++k) {
    f.sample[k] = idx[k];
    f.arc[k] = arc(idx[k]);
    f.position[k] = P.row(idx[k]).transpose();
  }
  return f;
}

}  // namespace colonmap::landmarks
