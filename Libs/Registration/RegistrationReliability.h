#pragma once
// Where a registration cannot be trusted (issue 20): a small bound is a promise, so where the
// evidence says the map may be wrong by more than its bound, the point is marked unreliable
// instead. Two levels:
//  - a segment is untrusted when the map rests on nothing the scans share: no matched fold and
//    curvature images that do not agree at any shift (the map is the conformal one alone), or
//    lengths between the scans that differ more than the colon stretches (the segment may hold
//    other anatomy in one scan), or flexures that were not chosen jointly for the pair (the
//    segments are the alignment's guess);
//  - a flexure between an untrusted segment and its neighbour is suspect (where an untrusted
//    segment begins and ends is uncertain too), and the neighbour's points within reach of it
//    are unreliable.
// Per vertex: trusted = segment trusted and not within reach of a suspect flexure end; reliable =
// trusted and a 90% bound within maxBound90Mm (a position known no better than that is no guide
// to where a finding lies). 7 mm, chosen on the uncertainty pool (2026-12-05, held back by seed;
// docs/accuracy.md): of the errors above 20 mm, 95% then had a bound above 20 mm or were marked
// unreliable (10 mm: 83%), at 19% of the points marked (10 mm: 12%): 3-9% on the pairs that
// register well (tube at deformation 0.5, GCA, VHM), 37-46% on the hard ones (tube at 1.0, VHF).
#include "Registration/RegistrationUncertainty.h"

#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace colonmap::registration {

struct ReliabilityOptions {
  double minCurvatureAgreement = 0.15;  // with no matched fold, curvature images correlating less: no evidence
  double maxLengthMismatch = 0.25;      // |log length ratio| above this: the segment may not be the same anatomy
  double flexureReachMm = 60.0;         // how far from a suspect flexure points are unreliable
  double maxBound90Mm = 7.0;            // a larger 90% bound is not reliable
};

struct SegmentTrust {
  bool trusted = true;
  std::vector<std::string> reasons;  // why not, one short phrase each
};

// evidence: the segment's (RegistrationUncertainty.h); flexuresJoint: false when the landmarks fell
// back (flexures not chosen jointly for the pair, or not in order).
SegmentTrust JudgeSegment(const SegmentEvidence& evidence, bool flexuresJoint, const ReliabilityOptions& options = {});

// 1 where trusted, 0 where not, per vertex of one segment. endSuspect: its v-min and v-max ends
// are suspect flexures (a neighbour across them is untrusted).
Eigen::VectorXd TrustedVertices(const UncertaintyComponents& components, bool trusted, const std::array<bool, 2>& endSuspect,
                                const ReliabilityOptions& options = {});

// 1 where reliable: trusted (0/1) and bound90 (mm) within options.maxBound90Mm.
Eigen::VectorXd ReliableVertices(const Eigen::VectorXd& trusted, const Eigen::VectorXd& bound90,
                                 const ReliabilityOptions& options = {});

}  // namespace colonmap::registration
