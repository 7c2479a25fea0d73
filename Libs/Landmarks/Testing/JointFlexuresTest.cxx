// Flexures chosen for both scans together (issue 19), with known answers: the centreline
// alignment on a curve with a stretched stretch, a pair where one scan's rules alone pick a
// different place than the other's, a flexure clear in one scan carried to the other, and the
// concurrent runner the pair uses.
#include "Landmarks/CentrelineAlignment.h"
#include "Landmarks/JointFlexures.h"

#include "Analysis/MidlineProjection.h"
#include "Core/Error.h"
#include "Core/RunConcurrently.h"

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <thread>

namespace colonmap::landmarks {
namespace {

// A space curve with bends of varying direction, parameter u in [0, 1000] (about arc length).
Eigen::Vector3d Curve(double u) {
  return {60.0 * std::cos(u / 45.0) + 0.05 * u, 50.0 * std::sin(u / 70.0), 0.6 * u + 20.0 * std::sin(u / 30.0)};
}

// Samples of Curve at the parameters given.
Eigen::MatrixXd Sample(const std::vector<double>& u) {
  Eigen::MatrixXd P(static_cast<Eigen::Index>(u.size()), 3);
  for (std::size_t i = 0; i < u.size(); ++i) P.row(static_cast<Eigen::Index>(i)) = Curve(u[i]).transpose();
  return P;
}

// b: the same curve with its stretch u in [300, 600] 12% longer (scaled about its start; a
// segment longer in one scan), the rest following, all shifted 15 mm (the patient moved). Both
// sampled at the same parameters (every 0.5), so sample i is the same place in both.
struct Pair {
  Eigen::MatrixXd a, b;
  std::vector<double> ua, ub;
};
Pair MakePair() {
  Pair p;
  for (double u = 0.0; u <= 1000.0; u += 0.5) p.ua.push_back(u);
  p.ub = p.ua;
  p.a = Sample(p.ua);
  p.b = p.a;
  const Eigen::RowVector3d origin = Curve(300.0).transpose();
  const Eigen::RowVector3d shift = origin + 1.12 * (Curve(600.0).transpose() - origin) - Curve(600.0).transpose();
  for (std::size_t i = 0; i < p.ua.size(); ++i) {
    const double u = p.ua[i];
    const Eigen::Index r = static_cast<Eigen::Index>(i);
    if (u > 300.0 && u <= 600.0) p.b.row(r) = origin + 1.12 * (p.a.row(r) - origin);
    if (u > 600.0) p.b.row(r) = p.a.row(r) + shift;
  }
  p.b.rowwise() += Eigen::RowVector3d(15.0, 0.0, 0.0);
  return p;
}

// Arc length along P at sample index i.
double ArcAt(const Eigen::MatrixXd& P, std::size_t i) { return analysis::ArcLength(P)(static_cast<Eigen::Index>(i)); }

TEST(JointFlexures, CentrelineAlignmentFindsTheSamePlaceAcrossAStretchedSegment) {
  const Pair p = MakePair();
  const CentrelineAlignment m(p.a, p.b);
  const Eigen::VectorXd arcA = analysis::ArcLength(p.a), arcB = analysis::ArcLength(p.b);
  // For a's samples at u = 100, 200, ..., 900: b's sample with the same u (the same index).
  double worst = 0.0;
  for (double u = 100.0; u <= 900.0; u += 100.0) {
    const Eigen::Index i = static_cast<Eigen::Index>(std::lround(u / 0.5));
    worst = std::max(worst, std::fabs(m.AToB(arcA(i)) - arcB(i)));
    EXPECT_NEAR(m.BToA(arcB(i)), arcA(i), 10.0) << "u " << u;
  }
  EXPECT_LT(worst, 10.0);
  // Proportional arc length would be off by more there (the stretch is local).
  const double L = arcA(arcA.size() - 1), LB = arcB(arcB.size() - 1);
  EXPECT_GT(std::fabs(arcA(1200) * LB / L - arcB(1200)), 15.0);
  EXPECT_LT(m.meanCost, 0.1);
}

TEST(JointFlexures, AnAlignmentToldInAnotherCurvesArcsIsTheSamePairing) {
  // Other curves through the same colons: each centreline with a straight 30 mm (a) and 50 mm (b)
  // lead-in before its anal end, so a place at arc x along the centreline is at x + 30 (x + 50)
  // along the other curve.
  const Pair p = MakePair();
  const CentrelineAlignment m(p.a, p.b);
  const auto leadIn = [](const Eigen::MatrixXd& P, double mm) {
    const Eigen::RowVector3d back = (P.row(0) - P.row(10)).normalized();
    Eigen::MatrixXd Q(P.rows() + 1, 3);
    Q << P.row(0) + mm * back, P;
    return Q;
  };
  const Eigen::MatrixXd a2 = leadIn(p.a, 30.0), b2 = leadIn(p.b, 50.0);
  const ArcMap onA(a2, p.a), onB(b2, p.b);
  EXPECT_NEAR(onA.Forward(130.0), 100.0, 0.5);
  EXPECT_NEAR(onA.Backward(100.0), 130.0, 0.5);
  const CentrelineAlignment told = m.InArcsOf(onA, onB);
  for (double x = 50.0; x <= 900.0; x += 50.0) {
    EXPECT_NEAR(told.AToB(x + 30.0), m.AToB(x) + 50.0, 1.0) << x;
    EXPECT_NEAR(told.BToA(m.AToB(x) + 50.0), x + 30.0, 1.0) << x;
  }
  // The lead-ins themselves lie before either centreline: they go to its start.
  EXPECT_NEAR(told.AToB(10.0), 50.0, 1.0);
}

FlexureCandidates Candidates(const std::array<std::vector<FlexureCandidate>, 4>& c) {
  FlexureCandidates out;
  out.flexure = c;
  for (int k = 0; k < 4; ++k)
    for (const FlexureCandidate& g : c[k])
      if (g.isDefault) out.byDefault.arc[k] = g.arc;
  out.runs = 100;
  return out;
}

TEST(JointFlexures, AWaveringRuleInOneScanDoesNotPairDifferentAnatomy) {
  // The same colon in both scans (b = a shifted, so the alignment is the identity). Scan a's
  // DSJ rule is nearly clear at 480 mm; scan b's default lands at 576 mm (70% of the runs), but
  // 30% of its runs see 483 mm (as GCA 00020's prone DSJ under seed 2 of the real-colon pairs).
  // Alone, the two scans would pair a DSJ 96 mm apart.
  Pair p = MakePair();
  p.b = p.a.rowwise() + Eigen::RowVector3d(0, 0, 5);
  const CentrelineAlignment m(p.a, p.b);
  const FlexureCandidate rsj{100, 1.0, true};
  const FlexureCandidates a = Candidates({{{{950, 1.0, true}}, {{750, 1.0, true}}, {{480, 0.9, true}, {575, 0.1, false}}, {rsj}}});
  const FlexureCandidates b = Candidates({{{{950, 1.0, true}}, {{750, 1.0, true}}, {{576, 0.7, true}, {483, 0.3, false}}, {rsj}}});
  const double L = analysis::ArcLength(p.a)(p.a.rows() - 1);
  const JointFlexureChoice c = ChooseFlexuresJointly(a, b, L, L, m, {"supine", "prone"});
  ASSERT_TRUE(c.consistent);
  // The pair that agrees (480 and 483 mm), each moved halfway to the other (identity alignment).
  EXPECT_NEAR(c.arc[0][2], 481.5, 1e-6);
  EXPECT_NEAR(c.arc[1][2], 481.5, 1e-6);
  EXPECT_EQ(c.how[2], "rechosen");
  EXPECT_NEAR(c.defaultDisagreementMm[2], 96.0, 3.0);
  for (int k : {0, 1, 3}) EXPECT_EQ(c.how[k], "agreed");
}

TEST(JointFlexures, AFlexureClearInOneScanCarriesOverToTheOther) {
  // Across the stretched segment: a's SF is clear (every run) at u = 650; b's SF wavers between
  // two wrong places (u = 420 and u = 780). The chosen b SF is a's, carried through the
  // alignment, within 10 mm of the b sample with the same u.
  const Pair p = MakePair();
  const CentrelineAlignment m(p.a, p.b);
  const auto arcOfU = [](const Eigen::MatrixXd& P, const std::vector<double>& us, double u) {
    std::size_t i = 0;
    while (i + 1 < us.size() && us[i] < u) ++i;
    return ArcAt(P, i);
  };
  const double sfA = arcOfU(p.a, p.ua, 650.0);
  const FlexureCandidates a = Candidates({{{{arcOfU(p.a, p.ua, 900.0), 1.0, true}},
                                           {{sfA, 1.0, true}},
                                           {{arcOfU(p.a, p.ua, 250.0), 1.0, true}},
                                           {{arcOfU(p.a, p.ua, 80.0), 1.0, true}}}});
  const FlexureCandidates b = Candidates({{{{arcOfU(p.b, p.ub, 900.0), 1.0, true}},
                                           {{arcOfU(p.b, p.ub, 420.0), 0.55, true}, {arcOfU(p.b, p.ub, 780.0), 0.45, false}},
                                           {{arcOfU(p.b, p.ub, 250.0), 1.0, true}},
                                           {{arcOfU(p.b, p.ub, 80.0), 1.0, true}}}});
  const JointFlexureChoice c =
      ChooseFlexuresJointly(a, b, ArcAt(p.a, p.ua.size() - 1), ArcAt(p.b, p.ub.size() - 1), m, {"supine", "prone"});
  ASSERT_TRUE(c.consistent);
  EXPECT_EQ(c.how[1], "carried from supine");
  EXPECT_NEAR(c.arc[0][1], sfA, 1e-9);
  EXPECT_NEAR(c.arc[1][1], arcOfU(p.b, p.ub, 650.0), 10.0);
  for (int k : {0, 2, 3}) EXPECT_EQ(c.how[k], "agreed");
}

TEST(JointFlexures, AFlexureOnBridgedWallIsTheOtherScansCarriedOver) {
  // The same colon in both scans (identity alignment). The supine splenic flexure lies in a
  // collapsed stretch bridged by virtual lumen: the smooth bridge cuts the bend, and the rule puts
  // it at 712 mm (38 mm off, as on tube seed 6 with one collapse); the prone scan saw it at
  // 750 mm. The two do not agree (30 mm), and seen wall decides: the prone flexure is carried
  // over. The control without the bridged flag carries the supine one (the tie keeps the first).
  // A bridged candidate within 30 mm of the seen one is no agreement either; two bridged ones
  // (a stretch collapsed in both scans) pair as before.
  Pair p = MakePair();
  p.b = p.a.rowwise() + Eigen::RowVector3d(0, 0, 5);
  const CentrelineAlignment m(p.a, p.b);
  const double L = analysis::ArcLength(p.a)(p.a.rows() - 1);
  FlexureCandidates a = Candidates({{{{950, 1.0, true}}, {{712, 1.0, true}}, {{480, 1.0, true}}, {{100, 1.0, true}}}});
  const FlexureCandidates b = Candidates({{{{950, 1.0, true}}, {{750, 1.0, true}}, {{480, 1.0, true}}, {{100, 1.0, true}}}});
  const JointFlexureChoice control = ChooseFlexuresJointly(a, b, L, L, m, {"supine", "prone"});
  EXPECT_EQ(control.how[1], "carried from supine");
  EXPECT_NEAR(control.arc[0][1], 712.0, 1e-9);
  a.flexure[1][0].bridged = true;
  const JointFlexureChoice c = ChooseFlexuresJointly(a, b, L, L, m, {"supine", "prone"});
  ASSERT_TRUE(c.consistent);
  EXPECT_EQ(c.how[1], "carried from prone");
  EXPECT_NEAR(c.arc[1][1], 750.0, 1e-9);
  EXPECT_NEAR(c.arc[0][1], 750.0, 3.0);
  for (int k : {0, 2, 3}) EXPECT_EQ(c.how[k], "agreed");
  a.flexure[1][0].arc = 735.0;
  const JointFlexureChoice near = ChooseFlexuresJointly(a, b, L, L, m, {"supine", "prone"});
  EXPECT_EQ(near.how[1], "carried from prone");
  EXPECT_NEAR(near.arc[0][1], 750.0, 3.0);
  FlexureCandidates bothBridged = b;
  bothBridged.flexure[1][0].bridged = true;
  const JointFlexureChoice both = ChooseFlexuresJointly(a, bothBridged, L, L, m, {"supine", "prone"});
  EXPECT_EQ(both.how[1], "agreed");
  EXPECT_NEAR(both.arc[0][1], 742.5, 1e-6);  // 735 and 750 agree: both halfway
  EXPECT_NEAR(both.arc[1][1], 742.5, 1e-6);
}

// Two places that agree through the alignment are still up to agreeMm apart in anatomy: both
// are moved halfway to the other, so the two scans' segments end at the same place of the colon
// (without it, HuBMAP VHM's DSJs lay 20-25 mm apart and its registration lost 1.1-1.4 mm).
TEST(JointFlexures, APairThatAgreesMeetsHalfway) {
  Pair p = MakePair();
  p.b = p.a.rowwise() + Eigen::RowVector3d(0, 0, 5);
  const CentrelineAlignment m(p.a, p.b);
  const double L = analysis::ArcLength(p.a)(p.a.rows() - 1);
  const FlexureCandidates a = Candidates({{{{950, 1.0, true}}, {{750, 1.0, true}}, {{470, 1.0, true}}, {{100, 1.0, true}}}});
  const FlexureCandidates b = Candidates({{{{950, 1.0, true}}, {{750, 1.0, true}}, {{494, 1.0, true}}, {{100, 1.0, true}}}});
  const JointFlexureChoice met = ChooseFlexuresJointly(a, b, L, L, m, {"supine", "prone"});
  EXPECT_EQ(met.how[2], "agreed");
  EXPECT_NEAR(met.arc[0][2], 482.0, 1e-6);
  EXPECT_NEAR(met.arc[1][2], 482.0, 1e-6);
  JointFlexureOptions apart;
  apart.meetHalfway = false;
  const JointFlexureChoice kept = ChooseFlexuresJointly(a, b, L, L, m, {"supine", "prone"}, apart);
  EXPECT_NEAR(kept.arc[0][2], 470.0, 1e-9);
  EXPECT_NEAR(kept.arc[1][2], 494.0, 1e-9);
}

TEST(JointFlexures, WithoutAnOrderedChoiceTheSegmentsComeFromTheAlignmentAndSaySo) {
  Pair p = MakePair();
  const CentrelineAlignment m(p.a, p.b);
  const double la = ArcAt(p.a, p.ua.size() - 1), lb = ArcAt(p.b, p.ub.size() - 1);
  // Scan b's RSJ lies above its DSJ, clearly (every run), a's RSJ is unclear (half the runs);
  // with one option per flexure kept (b's RSJ carried to a), no combination is in order: a's
  // own rules (in order) give all four, carried to b.
  const FlexureCandidates a = Candidates({{{{900, 1.0, true}}, {{700, 1.0, true}}, {{300, 1.0, true}}, {{100, 0.5, true}}}});
  const FlexureCandidates b = Candidates({{{{900, 1.0, true}}, {{700, 1.0, true}}, {{300, 1.0, true}}, {{330, 1.0, true}}}});
  JointFlexureOptions o;
  o.optionsPerFlexure = 1;
  const JointFlexureChoice c = ChooseFlexuresJointly(a, b, la, lb, m, {"supine", "prone"}, o);
  EXPECT_FALSE(c.consistent);
  EXPECT_TRUE(c.fallback);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(c.arc[0][k], a.byDefault.arc[k], 1e-9);
    EXPECT_NEAR(c.arc[1][k], m.AToB(a.byDefault.arc[k]), 1e-9);
    EXPECT_EQ(c.how[k], "fallback: from the alignment, supine's rules");
  }
  // Neither scan in order: each keeps its own, and says so.
  const JointFlexureChoice none = ChooseFlexuresJointly(b, b, lb, lb, m, {"supine", "prone"}, o);
  EXPECT_FALSE(none.consistent);
  EXPECT_FALSE(none.fallback);
  EXPECT_NEAR(none.arc[0][3], 330.0, 1e-9);
  EXPECT_EQ(none.how[3], "inconsistent: each scan's own rules kept");
}

TEST(RunConcurrently, RunsBothPropagatesErrorsAndCancelsTheWorker) {
  struct Host : ProgressSink {
    std::thread::id caller = std::this_thread::get_id();
    bool otherThread = false;
    int cancelAfter = -1, calls = 0;
    void Report(double) override {
      otherThread = otherThread || std::this_thread::get_id() != caller;
      if (cancelAfter >= 0 && ++calls > cancelAfter) throw Cancelled();
    }
  };
  Host host;
  std::atomic<int> done{0};
  RunConcurrently([&](ProgressSink& p) { p.Report(0.5); ++done; }, [&](ProgressSink& p) { p.Report(0.5); ++done; }, host);
  EXPECT_EQ(done.load(), 2);
  EXPECT_FALSE(host.otherThread);  // the host's sink is only called from its own thread
  EXPECT_THROW(RunConcurrently([](ProgressSink&) {}, [](ProgressSink&) { throw Error("second failed"); }, host), Error);
  EXPECT_THROW(RunConcurrently([](ProgressSink&) { throw Error("first failed"); }, [](ProgressSink&) {}, host), Error);
  // Cancel while the worker loops: it stops at its next Report and the call returns promptly.
  host.cancelAfter = 3;
  const auto start = std::chrono::steady_clock::now();
  std::atomic<bool> workerStopped{false};
  EXPECT_THROW(RunConcurrently(
                   [](ProgressSink& p) {
                     for (int i = 0; i < 1000; ++i) p.Report(i / 1000.0), std::this_thread::sleep_for(std::chrono::milliseconds(1));
                   },
                   [&](ProgressSink& p) {
                     try {
                       for (;;) p.Report(0.1), std::this_thread::sleep_for(std::chrono::milliseconds(1));
                     } catch (const Cancelled&) {
                       workerStopped = true;
                       throw;
                     }
                   },
                   host),
               Cancelled);
  EXPECT_TRUE(workerStopped.load());
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 0.5);
}

}  // namespace
}  // namespace colonmap::landmarks
