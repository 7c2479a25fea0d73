#include "Landmarks/JointFlexures.h"

#include <algorithm>
#include <cmath>

namespace colonmap::landmarks {

namespace {

struct Option {
  double arcA = 0.0, arcB = 0.0, worth = 0.0;
  std::string how;
};

std::vector<Option> OptionsFor(int k, const FlexureCandidates& a, const FlexureCandidates& b,
                               const CentrelineAlignment& m, const std::array<std::string, 2>& names,
                               const JointFlexureOptions& o) {
  // A candidate on bridged wall (a collapsed stretch) was found on the virtual tube, not on the
  // colon: it is worth nothing, never carried, and pairs only with another bridged one (its
  // "agreement" with a seen flexure is no evidence: tube seed 6, one collapse, agreed within 30 mm
  // and was 38 mm off). Where one scan saw the flexure, that one is carried over.
  const auto worth = [](const FlexureCandidate& c) { return c.bridged ? 0.0 : c.share; };
  std::vector<Option> out;
  for (const FlexureCandidate& ca : a.flexure[k])
    for (const FlexureCandidate& cb : b.flexure[k])
      if (ca.bridged == cb.bridged && std::fabs(m.AToB(ca.arc) - cb.arc) <= o.agreeMm) {
        // Two places that agree within agreeMm are still up to agreeMm apart: the same anatomy
        // is halfway between them (each scan's place and the other's carried over, averaged).
        const double arcA = o.meetHalfway ? 0.5 * (ca.arc + m.BToA(cb.arc)) : ca.arc;
        const double arcB = o.meetHalfway ? 0.5 * (cb.arc + m.AToB(ca.arc)) : cb.arc;
        out.push_back({arcA, arcB, ca.share + cb.share, ca.isDefault && cb.isDefault ? "agreed" : "rechosen"});
      }
  for (const FlexureCandidate& ca : a.flexure[k]) out.push_back({ca.arc, m.AToB(ca.arc), worth(ca), "carried from " + names[0]});
  for (const FlexureCandidate& cb : b.flexure[k]) out.push_back({m.BToA(cb.arc), cb.arc, worth(cb), "carried from " + names[1]});
  std::stable_sort(out.begin(), out.end(), [](const Option& x, const Option& y) { return x.worth > y.worth; });
  if (static_cast<int>(out.size()) > o.optionsPerFlexure) out.resize(static_cast<std::size_t>(o.optionsPerFlexure));
  return out;
}

// HF > SF > DSJ > RSJ, each gap and the ends at least minSegmentMm.
bool Ordered(const std::array<double, 4>& arc, double length, double gap) {
  return arc[3] >= gap && arc[2] - arc[3] >= gap && arc[1] - arc[2] >= gap && arc[0] - arc[1] >= gap &&
         length - arc[0] >= gap;
}

}  // namespace

JointFlexureChoice ChooseFlexuresJointly(const FlexureCandidates& a, const FlexureCandidates& b, double lengthA,
                                         double lengthB, const CentrelineAlignment& m,
                                         const std::array<std::string, 2>& names, const JointFlexureOptions& o) {
  JointFlexureChoice c;
  std::array<std::vector<Option>, 4> options;
  for (int k = 0; k < 4; ++k) {
    options[k] = OptionsFor(k, a, b, m, names, o);
    c.defaultDisagreementMm[k] = std::fabs(m.AToB(a.byDefault.arc[k]) - b.byDefault.arc[k]);
  }
  double best = -1.0;
  std::array<std::size_t, 4> pick{};
  std::array<std::size_t, 4> i{};
  for (i[0] = 0; i[0] < options[0].size(); ++i[0])
    for (i[1] = 0; i[1] < options[1].size(); ++i[1])
      for (i[2] = 0; i[2] < options[2].size(); ++i[2])
        for (i[3] = 0; i[3] < options[3].size(); ++i[3]) {
          std::array<double, 4> arcA{}, arcB{};
          double worth = 0.0;
          for (int k = 0; k < 4; ++k) {
            const Option& op = options[k][i[k]];
            arcA[k] = op.arcA, arcB[k] = op.arcB, worth += op.worth;
          }
          // Strictly better only: ties keep the earlier (higher-worth-first) combination.
          if (worth > best + 1e-12 && Ordered(arcA, lengthA, o.minSegmentMm) && Ordered(arcB, lengthB, o.minSegmentMm))
            best = worth, pick = i;
        }
  if (best < 0) {
    // Fallback: no ordered choice among the options. The segments then come from the alignment
    // alone: the scan whose own rules are in order gives all four, carried to the other.
    c.consistent = false;
    c.arc[0] = a.byDefault.arc;
    c.arc[1] = b.byDefault.arc;
    const bool aOrdered = Ordered(a.byDefault.arc, lengthA, o.minSegmentMm);
    const bool bOrdered = Ordered(b.byDefault.arc, lengthB, o.minSegmentMm);
    for (int k = 0; k < 4; ++k) {
      if (aOrdered) c.arc[1][k] = m.AToB(a.byDefault.arc[k]);
      else if (bOrdered) c.arc[0][k] = m.BToA(b.byDefault.arc[k]);
      c.how[k] = aOrdered   ? "fallback: from the alignment, " + names[0] + "'s rules"
                 : bOrdered ? "fallback: from the alignment, " + names[1] + "'s rules"
                            : "inconsistent: each scan's own rules kept";
    }
    c.fallback = aOrdered || bOrdered;
    return c;
  }
  c.worth = best;
  for (int k = 0; k < 4; ++k) {
    const Option& op = options[k][pick[k]];
    c.arc[0][k] = op.arcA;
    c.arc[1][k] = op.arcB;
    c.how[k] = op.how;
  }
  return c;
}

}  // namespace colonmap::landmarks
