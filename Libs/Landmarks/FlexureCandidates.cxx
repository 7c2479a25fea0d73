#include "Landmarks/FlexureCandidates.h"

#include "Core/Error.h"

#include <algorithm>

namespace colonmap::landmarks {

namespace {

// The threshold grid: each rule's deciding thresholds at, below and above their defaults.
std::vector<FlexureOptions> Variants(const FlexureOptions& d) {
  std::vector<FlexureOptions> out;
  for (double hysteresis : {0.6, 1.0, 1.6})
    for (double lower : {0.6, 1.0, 1.6})
      for (double turn : {0.8, 1.0, 1.2})
        for (double tangent : {1.0, 2.0})
          for (double exit : {0.8, 1.0, 1.2}) {
            FlexureOptions o = d;
            o.heightHysteresisMm = d.heightHysteresisMm * hysteresis;
            o.descendingLowerFraction = std::min(0.9, d.descendingLowerFraction * lower);
            o.sigmoidTurn = d.sigmoidTurn * turn;
            o.turnTangentMm = d.turnTangentMm * tangent;
            o.rectumExitDeg = d.rectumExitDeg * exit;
            out.push_back(o);
          }
  return out;
}

}  // namespace

FlexureCandidates FindFlexureCandidates(const Eigen::MatrixXd& P, const Eigen::VectorXd& arc,
                                        const FlexureOptions& defaults, double groupMm) {
  FlexureCandidates c;
  c.byDefault = FindFlexures(P, arc, defaults);  // throws with what it found
  std::array<std::vector<double>, 4> found;
  for (const FlexureOptions& o : Variants(defaults)) {
    try {
      const Flexures f = FindFlexures(P, arc, o);
      for (int k = 0; k < 4; ++k) found[k].push_back(f.arc[k]);
      ++c.runs;
    } catch (const Error&) {
      // a variant that cannot find all four casts no vote
    }
  }
  for (int k = 0; k < 4; ++k) {
    std::vector<double>& a = found[k];
    // The default thresholds are also a point of the grid, so their place counts twice: a
    // slight preference for the rules as tuned (the measured figures were made so; dropping it
    // moves the group medians by a few mm).
    a.push_back(c.byDefault.arc[k]);
    std::sort(a.begin(), a.end());
    std::size_t from = 0;
    for (std::size_t i = 1; i <= a.size(); ++i) {
      if (i < a.size() && a[i] - a[i - 1] <= groupMm) continue;
      FlexureCandidate g;
      g.arc = a[from + (i - from) / 2];
      g.share = static_cast<double>(i - from) / static_cast<double>(a.size());
      g.isDefault = c.byDefault.arc[k] >= a[from] && c.byDefault.arc[k] <= a[i - 1];
      c.flexure[k].push_back(g);
      from = i;
    }
    std::stable_sort(c.flexure[k].begin(), c.flexure[k].end(),
                     [](const FlexureCandidate& x, const FlexureCandidate& y) { return x.share > y.share; });
  }
  return c;
}

}  // namespace colonmap::landmarks
