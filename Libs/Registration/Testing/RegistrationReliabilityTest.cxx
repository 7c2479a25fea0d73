// Where the registration says it cannot be trusted (RegistrationReliability.h), and the distance
// to a flexure end that the uncertainty model reads (RegistrationUncertainty.h), on known answers.
#include "Registration/RegistrationReliability.h"
#include "Registration/RegistrationUncertainty.h"

#include "CylinderSegment.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace colonmap::registration;

TEST(RegistrationReliability, SegmentWithoutSharedEvidenceIsUntrusted) {
  SegmentEvidence e;
  e.matchesPer100mm = 1.5;
  e.curvatureAgreement = 0.05;
  EXPECT_TRUE(JudgeSegment(e, true).trusted);  // matched folds carry it
  e.matchesPer100mm = 0.0;
  const SegmentTrust none = JudgeSegment(e, true);
  EXPECT_FALSE(none.trusted);
  ASSERT_EQ(none.reasons.size(), 1u);
  e.curvatureAgreement = 0.4;
  EXPECT_TRUE(JudgeSegment(e, true).trusted);  // the curvature images agree
  e.lengthMismatch = std::log(1.4);
  EXPECT_FALSE(JudgeSegment(e, true).trusted);
  e.lengthMismatch = 0.0;
  const SegmentTrust fallback = JudgeSegment(e, false);
  EXPECT_FALSE(fallback.trusted);
  EXPECT_EQ(fallback.reasons.front(), "flexures not chosen jointly");
}

TEST(RegistrationReliability, FlexureEndDistancesAndSuspectEnds) {
  // A 1 x 2 strip on a cylinder of circumference 100 mm: 200 mm long, v from 0 to 2.
  const int nu = 20, nv = 40;
  const FlatSegment s = colonmap::registration::testing::CylinderSegment(nu, nv, 2.0);
  const Eigen::VectorXd K = Eigen::VectorXd::Ones(s.F.rows());
  const Eigen::MatrixXd h = Eigen::MatrixXd::Zero(s.uv.rows(), 2);
  SegmentEvidence e;
  e.flexureAtEnd = {false, true};  // a tip at v = 0, a flexure at v = 2 (like segment R)
  const VertexUncertainty U = EstimateUncertainty(s, h, K, {}, e);
  const int bottom = 0, top = nv * (nu + 1), middle = (nv / 2) * (nu + 1);
  EXPECT_NEAR(FlatLengthMm(s), 200.0, 2.0);
  EXPECT_NEAR(U.components.endMm[0](top), 200.0, 2.0);
  EXPECT_NEAR(U.components.endMm[1](top), 0.0, 1e-9);
  EXPECT_NEAR(U.components.flexureMm(bottom), 200.0, 2.0);  // the v-min end is a tip, not a flexure
  EXPECT_NEAR(U.components.flexureMm(middle), 100.0, 1.0);
  EXPECT_GT(U.median(top), U.median(middle)) << "the model must widen the bound near a flexure";
  // No flexure end at all: the constant.
  e.flexureAtEnd = {false, false};
  EXPECT_EQ(EstimateUncertainty(s, h, K, {}, e).components.flexureMm(middle), kNoFlexureMm);

  // Reliability: a suspect v-max end makes the last 60 mm unreliable, the rest stays reliable.
  const Eigen::VectorXd r = TrustedVertices(U.components, true, {false, true});
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    EXPECT_EQ(r(i), U.components.endMm[1](i) < 60.0 ? 0.0 : 1.0) << "vertex " << i;
  }
  EXPECT_EQ(TrustedVertices(U.components, false, {false, false}).maxCoeff(), 0.0);
  EXPECT_EQ(TrustedVertices(U.components, true, {false, false}).minCoeff(), 1.0);
  // Reliable: trusted and a bound within 10 mm.
  const Eigen::VectorXd bound = (Eigen::VectorXd(4) << 5.0, 10.0, 10.5, 30.0).finished();
  const Eigen::VectorXd trusted = (Eigen::VectorXd(4) << 1.0, 1.0, 1.0, 0.0).finished();
  EXPECT_EQ(ReliableVertices(trusted, bound), (Eigen::VectorXd(4) << 1.0, 1.0, 0.0, 0.0).finished());
}

TEST(RegistrationUncertainty, CurvatureWidensTheBoundOnABump) {
  // Mean curvature 0.3 /mm (a polyp of about 3 mm radius) on a patch of rows, 0.02 elsewhere.
  const int nu = 20, nv = 40;
  const FlatSegment s = colonmap::registration::testing::CylinderSegment(nu, nv, 2.0);
  const Eigen::VectorXd K = Eigen::VectorXd::Ones(s.F.rows());
  const Eigen::MatrixXd h = Eigen::MatrixXd::Zero(s.uv.rows(), 2);
  Eigen::VectorXd H = Eigen::VectorXd::Constant(s.uv.rows(), 0.02);
  for (int row = 18; row <= 22; ++row)
    for (int col = 8; col <= 12; ++col) H(row * (nu + 1) + col) = 0.3;
  const VertexUncertainty U = EstimateUncertainty(s, h, K, {}, SegmentEvidence{}, H);
  const int bump = 20 * (nu + 1) + 10, flat = 5 * (nu + 1) + 10;
  EXPECT_NEAR(U.components.curvature(flat), 0.2, 1e-9);  // 10 mm x 0.02 /mm
  EXPECT_GT(U.components.curvature(bump), 2.0);          // smoothed over two rings, still high
  EXPECT_LE(U.components.curvature.maxCoeff(), 5.0);
  EXPECT_GT(U.median(bump), U.median(flat));
  // Without curvature the input is 0 everywhere.
  EXPECT_EQ(EstimateUncertainty(s, h, K, {}, SegmentEvidence{}).components.curvature.maxCoeff(), 0.0);
}
