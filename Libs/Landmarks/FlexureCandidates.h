#pragma once
// Alternatives for each flexure of one scan (issue 19): the flexure rules (Flexures.h) run with
// their thresholds varied over a small grid around the defaults; the positions they give are
// grouped along the centreline, and each group's share of the runs says how clear that choice
// is in this scan. A flexure whose rule sits on a knife edge (a real DSJ where the sigmoid's
// turn is just at the threshold) shows two groups; a clear one shows one.
#include "Landmarks/Flexures.h"

#include <array>
#include <vector>

namespace colonmap::landmarks {

struct FlexureCandidate {
  double arc = 0.0;        // median arc length of the group (mm from the anal end)
  double share = 0.0;      // fraction of the rule runs that put the flexure in this group
  bool isDefault = false;  // the default thresholds' choice lies in this group
  bool bridged = false;    // on wall not seen (a collapsed stretch, BridgedWall.h): worth nothing jointly
};

struct FlexureCandidates {
  std::array<std::vector<FlexureCandidate>, 4> flexure;  // HF, SF, DSJ, RSJ; by decreasing share
  Flexures byDefault;  // the rules with the given (default) thresholds
  int runs = 0;        // rule runs that found all four flexures
};

// P, arc: the curve the rules run on (FindFlexures). groupMm: positions closer than this along
// the curve (chained) form one group. Throws colonmap::Error when the default rules fail (the
// message says what they found).
FlexureCandidates FindFlexureCandidates(const Eigen::MatrixXd& P, const Eigen::VectorXd& arc,
                                        const FlexureOptions& defaults, double groupMm = 10.0);

}  // namespace colonmap::landmarks
