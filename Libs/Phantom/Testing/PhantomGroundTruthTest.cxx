// Ground truth: evaluation points, polyps, taeniae, flexures, centreline samples.
#include "PhantomTestUtils.h"

#include <gtest/gtest.h>

#include <set>

using namespace colonmap;
using namespace colonmap::phantom;
using namespace colonmap::phantom::testing;

TEST(PhantomGroundTruth, EvaluationPointsOnTheWallSpreadAndMatchedAcrossScans) {
  PhantomOptions o = CoarseOptions(2, 0.5);
  const ColonAnatomy a = MakeAnatomy(o);
  const ScanGeometry sup = MakeScan(a, Posture::Supine, o), pro = MakeScan(a, Posture::Prone, o);
  const TriangleMesh ws = TrueWall(sup, o), wp = TrueWall(pro, o);
  const MarkupList es = EvaluationPoints(sup), ep = EvaluationPoints(pro);
  ASSERT_EQ(es.points.size(), 200u);
  ASSERT_EQ(ep.points.size(), 200u);
  EXPECT_EQ(es.points.front().label, "E001");
  EXPECT_EQ(es.points.back().label, "E200");
  std::set<int> segments;
  for (std::size_t i = 0; i < es.points.size(); ++i) {
    const EvaluationSite& e = a.evaluationSites[i];
    EXPECT_EQ(es.points[i].label, ep.points[i].label);
    EXPECT_EQ(ep.points[i].position, pro.WallPoint(e.s, e.theta));
    EXPECT_EQ(es.points[i].position, sup.WallPoint(e.s, e.theta));
    segments.insert(a.SegmentOf(e.s));
    EXPECT_EQ(a.PolypDepth(e.s, e.theta), 0.0) << e.label;
    // On the piecewise-linear truth mesh: within its chordal error (~0.1 mm on smooth wall, a
    // few tenths on fold crests).
    EXPECT_LT(DistanceToWall(ws, o.meshPointsAround, a.length, es.points[i].position, e.s), 0.6) << e.label;
    EXPECT_LT(DistanceToWall(wp, o.meshPointsAround, a.length, ep.points[i].position, e.s), 0.6) << e.label;
  }
  EXPECT_EQ(segments.size(), 5u);
}

TEST(PhantomGroundTruth, PolypTopsOnTheLumenSide) {
  PhantomOptions o = CoarseOptions(3, 1.0);
  const ColonAnatomy a = MakeAnatomy(o);
  for (Posture posture : {Posture::Supine, Posture::Prone}) {
    const ScanGeometry scan = MakeScan(a, posture, o);
    const TriangleMesh w = TrueWall(scan, o);
    const MarkupList p = Polyps(scan);
    ASSERT_EQ(p.points.size(), a.polyps.size());
    for (std::size_t i = 0; i < a.polyps.size(); ++i) {
      const Polyp& q = a.polyps[i];
      EXPECT_EQ(p.points[i].label, q.label);
      EXPECT_EQ(p.points[i].position, scan.WallPoint(q.s, q.theta));
      EXPECT_NE(p.points[i].description.find(q.pedunculated ? "pedunculated" : "sessile"), std::string::npos);
      // The top is the innermost point around: nearer to the centreline than the polyp's base.
      const double top = scan.WallRadius(q.s, q.theta);
      EXPECT_LT(top, scan.WallRadius(q.s + q.footRadius + 1.0, q.theta) - 0.4 * q.height);
      EXPECT_LT(DistanceToWall(w, o.meshPointsAround, a.length, p.points[i].position, q.s), 0.6);
    }
  }
}

TEST(PhantomGroundTruth, TaeniaeFlexuresAndCenterline) {
  PhantomOptions o = CoarseOptions(1, 0.5);
  const ColonAnatomy a = MakeAnatomy(o);
  const ScanGeometry sup = MakeScan(a, Posture::Supine, o), pro = MakeScan(a, Posture::Prone, o);
  for (const ScanGeometry* scan : {&sup, &pro}) {
    const std::vector<CurveSamples> t = Taeniae(*scan, 5.0);
    ASSERT_EQ(t.size(), 3u);
    EXPECT_EQ(t[0].name, "TL");
    EXPECT_EQ(t[1].name, "TO");
    EXPECT_EQ(t[2].name, "TM");
    for (const CurveSamples& c : t) {
      EXPECT_EQ(c.materialS[0], 0.0);
      EXPECT_DOUBLE_EQ(c.materialS[c.materialS.size() - 1], a.flexureS[kSigmoidRectum]);
      for (Eigen::Index i = 0; i < c.points.rows(); ++i) {
        EXPECT_EQ(Eigen::Vector3d(c.points.row(i)), scan->WallPoint(c.materialS[i], c.theta[i]));
        EXPECT_NEAR(a.FoldDepth(c.materialS[i], c.theta[i], 1.0), 0.0, 1e-12);  // folds stop at the taeniae
      }
    }
    const MarkupList f = Flexures(*scan);
    ASSERT_EQ(f.points.size(), 4u);
    const char* names[] = {"HF", "SF", "DSJ", "RSJ"};
    for (int k = 0; k < 4; ++k) {
      EXPECT_EQ(f.points[k].label, names[k]);
      EXPECT_LT((f.points[k].position - scan->CenterPoint(a.flexureS[k])).norm(), 1e-12);
    }
    const CurveSamples cl = CenterlineSamples(*scan, 2.0);
    EXPECT_NEAR(cl.arcLength[cl.arcLength.size() - 1], scan->centerline.Length(), 1e-9);
    for (Eigen::Index i = 1; i < cl.points.rows(); ++i) {
      EXPECT_NEAR(cl.arcLength[i] - cl.arcLength[i - 1], 2.0, 0.05);
      EXPECT_NEAR((cl.points.row(i) - cl.points.row(i - 1)).norm(), 2.0, 0.05);  // arc length ~ chord
      EXPECT_GT(cl.materialS[i], cl.materialS[i - 1]);
    }
    EXPECT_EQ(ToMarkups(cl).points.size(), static_cast<std::size_t>(cl.points.rows()));
  }
}
