#pragma once
// The flexures of the supine and the prone scan chosen together (issue 19). The scans are the
// same colon: each flexure must sit at the same place of it in both (through the centreline
// alignment, CentrelineAlignment.h), and in order in each. Per flexure the options are
//  - a pair of candidate groups (FlexureCandidates.h), one per scan, that the alignment puts
//    within agreeMm of each other: worth the sum of their shares;
//  - one scan's candidate carried to the other through the alignment: worth its share alone.
// The four flexures are chosen together (the best few options of each, every combination that
// keeps HF > SF > DSJ > RSJ at least minSegmentMm apart and inside the caps in both scans) for
// the largest total worth. So a flexure that is clear in one scan carries over to the other,
// and a rule that wavers in one scan cannot pair different anatomy. When no combination is in
// order, the segments are defined from the alignment (see `fallback`).
#include "Landmarks/CentrelineAlignment.h"
#include "Landmarks/FlexureCandidates.h"

#include <array>
#include <string>

namespace colonmap::landmarks {

struct JointFlexureOptions {
  double agreeMm = 30.0;       // a pair of candidates closer than this through the alignment agrees
  double minSegmentMm = 40.0;  // shortest segment allowed between flexures (and from the ends)
  int optionsPerFlexure = 6;
  bool meetHalfway = true;     // a pair that agrees: both moved halfway to the other through the alignment
};

struct JointFlexureChoice {
  std::array<std::array<double, 4>, 2> arc{};  // per scan (0 = a, 1 = b): HF, SF, DSJ, RSJ
  // Per flexure how it was chosen: "agreed" (both scans' default rules, within agreeMm),
  // "rechosen" (another pair of candidates that agree), "carried from <a|b>".
  std::array<std::string, 4> how;
  // The default rules' disagreement through the alignment (mm): |AToB(a) - b|.
  std::array<double, 4> defaultDisagreementMm{};
  double worth = 0.0;  // total worth of the choice (8 at most)
  // false: no ordered choice among the options. Then, when one scan's own rules are in order,
  // all four come from it, carried to the other through the alignment (fallback = true; the
  // segments are the alignment's, not both scans' anatomy); otherwise each scan keeps its own.
  bool consistent = true;
  bool fallback = false;
};

// lengthA, lengthB: the centreline lengths (the candidates' arcs are along them).
// names: what the two scans are called in `how` ("supine", "prone").
JointFlexureChoice ChooseFlexuresJointly(const FlexureCandidates& a, const FlexureCandidates& b, double lengthA,
                                         double lengthB, const CentrelineAlignment& alignment,
                                         const std::array<std::string, 2>& names,
                                         const JointFlexureOptions& options = {});

}  // namespace colonmap::landmarks
