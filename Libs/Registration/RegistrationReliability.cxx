#include "Registration/RegistrationReliability.h"

namespace colonmap::registration {

SegmentTrust JudgeSegment(const SegmentEvidence& e, bool flexuresJoint, const ReliabilityOptions& o) {
  SegmentTrust t;
  if (e.matchesPer100mm <= 0.0 && e.curvatureAgreement < o.minCurvatureAgreement)
    t.reasons.push_back("no matched fold and the curvature images do not agree");
  if (e.lengthMismatch > o.maxLengthMismatch) t.reasons.push_back("lengths differ between the scans");
  if (!flexuresJoint) t.reasons.push_back("flexures not chosen jointly");
  t.trusted = t.reasons.empty();
  return t;
}

Eigen::VectorXd TrustedVertices(const UncertaintyComponents& c, bool trusted, const std::array<bool, 2>& endSuspect,
                                const ReliabilityOptions& o) {
  const Eigen::Index n = c.flexureMm.size();
  Eigen::VectorXd reliable = Eigen::VectorXd::Constant(n, trusted ? 1.0 : 0.0);
  if (!trusted) return reliable;
  for (int e = 0; e < 2; ++e)
    if (endSuspect[e] && c.endMm[e].size() == n)
      reliable = (c.endMm[e].array() < o.flexureReachMm).select(0.0, reliable.array()).matrix();
  return reliable;
}

Eigen::VectorXd ReliableVertices(const Eigen::VectorXd& trusted, const Eigen::VectorXd& bound90, const ReliabilityOptions& o) {
  return (bound90.array() <= o.maxBound90Mm).select(trusted.array(), 0.0).matrix();
}

}  // namespace colonmap::registration
