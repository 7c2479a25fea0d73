#include "Flexures.h"

#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

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

Eigen::Index LowestBetween(const Eigen::MatrixXd& P, const Eigen::VectorXd& arc, double arcFrom, double arcTo) {
  const double a = std::min(arcFrom, arcTo), b = std::max(arcFrom, arcTo);
  Eigen::Index best = -1;
  for (Eigen::Index i = 0; i < P.rows() && i < arc.size(); ++i)
    if (arc(i) > a && arc(i) < b && (best < 0 || P(i, 2) < P(best, 2))) best = i;
  return best;
}

namespace {

int SharpestNear(const Eigen::VectorXd& bend, int i, int r) {
  const int n = static_cast<int>(bend.size());
  int best = i;
  for (int j = std::max(0, i - r); j <= std::min(n - 1, i + r); ++j)
    if (bend(j) > bend(best)) best = j;
  return best;
}

// Walking from `start` by `dir` (not reaching `stop`): the first peak (want +1) or trough
// (want -1) of z with hysteresis h. The run starts once z has moved by more than h in the wanted
// direction from its extreme so far (an initial run the other way is skipped); it ends when z
// falls back by more than h from the run's extreme, which is returned. A run still going at
// `stop` returns its extreme; no run at all returns -1.
int FirstExtremum(const Eigen::VectorXd& z, int start, int dir, int stop, double h, int want) {
  const int n = static_cast<int>(z.size());
  int low = start, best = -1;
  for (int i = start; i != stop && i >= 0 && i < n; i += dir) {
    const double v = want * z(i);
    if (best < 0) {
      if (v < want * z(low)) low = i;
      if (v - want * z(low) > h) best = i;
    } else if (v > want * z(best)) {
      best = i;
    } else if (want * z(best) - v > h) {
      return best;
    }
  }
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

  const Eigen::VectorXd z = P.col(2);
  const double h = o.heightHysteresisMm;
  // HF: the ascending colon's climb from the cecal end, up to its first peak (see the header).
  const int top = FirstExtremum(z, n - 1, -1, sf, h, +1);
  if (top < 0) fail("the colon does not rise from the cecum toward the splenic flexure");
  const int tw = std::max(1, static_cast<int>(std::round(o.turnTangentMm / step)));
  // Unit direction of travel toward the anus at sample i (chord over +-tw samples).
  const auto travel = [&](int i) -> Eigen::RowVector3d {
    const Eigen::RowVector3d t = P.row(std::clamp(i - tw, 0, n - 1)) - P.row(std::clamp(i + tw, 0, n - 1));
    return t.norm() > 0 ? Eigen::RowVector3d(t / t.norm()) : Eigen::RowVector3d::Zero();
  };
  int hf = top;
  const double climb = std::sin(o.hepaticClimbDeg * M_PI / 180.0);
  for (int i = top; i < n - 1; ++i)
    if (travel(i)(2) > climb) {
      hf = i;
      break;
    }
  if (hf <= sf) fail("the hepatic flexure is not on the cecum side of the splenic flexure");
  found += ", HF at " + Mm(arc(hf));
  // DSJ: the end of the descent from SF, or before it where the colon turns forward and medially.
  const int trough = FirstExtremum(z, sf, -1, -1, h, -1);
  if (trough < 0) fail("no end of the descending colon below the splenic flexure");
  const double lowest = z(trough) + o.descendingLowerFraction * (z(sf) - z(trough));
  const double norm = std::hypot(1.0, o.sigmoidMedialWeight);
  // The descending colon's own slope: the median vertical part of travel above the lowest part.
  std::vector<double> slopes;
  for (int i = sf; i > trough; --i)
    if (z(i) > lowest) slopes.push_back(travel(i)(2));
  double plunge = -1.0;
  if (!slopes.empty()) {
    std::nth_element(slopes.begin(), slopes.begin() + slopes.size() / 2, slopes.end());
    plunge = o.sigmoidSlowing * std::min(0.0, slopes[slopes.size() / 2]);
  }
  const double level = -std::sin(o.sigmoidMaxDescentDeg * M_PI / 180.0);
  int dsj = trough;
  for (int i = sf; i > trough; --i) {
    if (z(i) > lowest) continue;
    const Eigen::RowVector3d t = travel(i);
    // Still descending (as steeply as above, or steeper than sigmoidMaxDescentDeg): the
    // descending colon, turned.
    if (t(2) < std::max(plunge, level)) continue;
    if ((-t(1) - o.sigmoidMedialWeight * t(0)) / norm > o.sigmoidTurn) {
      dsj = i;
      break;
    }
  }
  if (dsj <= 0) fail("no end of the descending colon above the anal end");
  found += ", DSJ at " + Mm(arc(dsj));
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
