// Pieces of a colon split by collapsed stretches (issue 21): the ends of one piece, the order
// of several (known answers, including one that the nearest end gets wrong), and the pieces
// the segmentation keeps on phantoms with collapses, checked against the material s of the
// true colon.
#include "Phantom/Phantom.h"
#include "Segmentation/LumenSegmentation.h"
#include "Segmentation/PieceBridge.h"
#include "Segmentation/PieceOrder.h"
#include "Segmentation/PieceShape.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace colonmap;
using namespace colonmap::segmentation;

namespace {

PieceEnd End(double x, double y, double z, double ox, double oy, double oz) {
  PieceEnd e;
  e.point = Eigen::Vector3d(x, y, z);
  e.outward = Eigen::Vector3d(ox, oy, oz).normalized();
  return e;
}
PieceShape Shape(const PieceEnd& a, const PieceEnd& b) {
  PieceShape s;
  s.ends = {a, b};
  s.lengthMm = (a.point - b.point).norm();
  return s;
}

}  // namespace

TEST(PieceShape, StraightCylinderEndsAndDirections) {
  // Radius 10 mm, x in [-50, 50], 1 mm voxels, centred on the grid.
  Volume<unsigned char> m;
  m.size = {{121, 31, 31}};
  m.origin = Eigen::Vector3d(-60, -15, -15);
  m.Allocate(0);
  for (std::size_t k = 0; k < 31; ++k)
    for (std::size_t j = 0; j < 31; ++j)
      for (std::size_t i = 0; i < 121; ++i) {
        const Eigen::Vector3d p = m.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
        if (std::abs(p.x()) <= 50 && p.y() * p.y() + p.z() * p.z() <= 100) m.At(i, j, k) = 1;
      }
  const PieceShape s = MeasurePieceShape(m);
  // Rim to rim: sqrt(100^2 + 20^2) = 102 mm, plus the blocks' zigzag.
  EXPECT_GT(s.lengthMm, 95.0);
  EXPECT_LT(s.lengthMm, 112.0);
  for (const PieceEnd& e : s.ends) {
    // The centroid of the lumen 5-15 mm in, on the axis; the lumen runs out along x.
    EXPECT_NEAR(std::abs(e.point.x()), 40.0, 4.0);
    EXPECT_LT(std::hypot(e.point.y(), e.point.z()), 2.0);
    EXPECT_GT(std::abs(e.outward.x()), 0.95);
    EXPECT_GT(e.outward.x() * e.point.x(), 0.0);  // outward, not inward
  }
}

TEST(PieceOrder, SigmoidLoopCrossingTheDescendingNearestEndIsWrong) {
  // The colon: caecum (x = -100) ... descending colon down x = 100, collapse, a sigmoid loop
  // that turns back up and crosses medially 25 mm in front of the descending colon's end,
  // collapse, the rectum down to the anus. Input shuffled and pieces reversed.
  const PieceShape proximal = Shape(End(-100, 0, -120, 0, 0, -1), End(100, 0, -100, 0, 0, -1));
  const PieceShape sigmoid = Shape(End(100, 0, -145, 0, 0, 1), End(100, -25, -100, -1, 0, 0));
  const PieceShape rectum = Shape(End(40, -25, -110, 1, 0, 0), End(0, 0, -250, 0, 0, -1));
  const std::vector<PieceShape> pieces = {Shape(sigmoid.ends[1], sigmoid.ends[0]), rectum, proximal};
  // The naive choice: the end nearest to the descending colon's end is the sigmoid's far end.
  const Eigen::Vector3d d = proximal.ends[1].point;
  ASSERT_LT((d - sigmoid.ends[1].point).norm(), (d - sigmoid.ends[0].point).norm());

  const PieceChain chain = OrderPieces(pieces, 2, PieceOrderOptions{});
  ASSERT_EQ(chain.pieces, (std::vector<int>{2, 0, 1}));
  EXPECT_EQ(chain.caecalEnd, (std::vector<int>{0, 1, 0}));  // the sigmoid was given reversed
  ASSERT_EQ(chain.gapMm.size(), 2u);
  EXPECT_NEAR(chain.gapMm[0], 45.0, 1e-9);
  EXPECT_NEAR(chain.gapMm[1], std::hypot(60.0, 10.0), 1e-9);
}

TEST(PieceOrder, FarOrSidewaysPiecesAreLeftOutAndOnePieceIsOrientedByTheCaecum) {
  const PieceShape colon = Shape(End(100, 0, -100, 0, 0, -1), End(-100, 0, -120, 0, 0, -1));
  const PieceShape far = Shape(End(100, 0, -300, 0, 0, 1), End(100, 0, -400, 0, 0, -1));     // 200 mm away
  const PieceShape sideways = Shape(End(150, 0, -100, 1, 0, 0), End(150, 0, -30, 0, 0, 1));  // 50 mm, facing away
  const PieceChain chain = OrderPieces({colon, far, sideways}, 0, PieceOrderOptions{});
  ASSERT_EQ(chain.pieces, (std::vector<int>{0}));
  EXPECT_EQ(chain.caecalEnd, (std::vector<int>{1}));  // x = -100 is the caecum
  EXPECT_TRUE(chain.gapMm.empty());
  EXPECT_FALSE(std::isfinite(LinkCost(colon.ends[0], far.ends[0], PieceOrderOptions{})));
}

// Phantom pairs with two collapsed stretches (2.5 mm, air only): every scan keeps one piece
// more than its collapses, the pieces follow the colon from the caecum (their material s
// ranges are in order and lie between the collapses), and label 1 is the largest piece.
TEST(PhantomSegmentation, CollapsedColonKeepsEveryPieceInOrderFromTheCaecum) {
  for (std::uint32_t seed = 1; seed <= 4; ++seed) {
    phantom::PhantomOptions o;
    o.seed = seed;
    o.fluid = false;
    o.collapses = 2;
    o.spacing = Eigen::Vector3d(2.5, 2.5, 2.5);
    const phantom::ColonAnatomy anatomy = phantom::MakeAnatomy(o);
    ASSERT_EQ(anatomy.collapses.size(), 2u);
    for (const phantom::Posture posture : {phantom::Posture::Supine, phantom::Posture::Prone}) {
      SCOPED_TRACE("seed " + std::to_string(seed) + (posture == phantom::Posture::Supine ? " supine" : " prone"));
      NullProgress none;
      const phantom::ScanGeometry scan = phantom::MakeScan(anatomy, posture, o);
      std::vector<std::pair<double, double>> closed;
      for (const auto& c : anatomy.collapses)
        if (posture == phantom::Posture::Supine ? c.supine : c.prone) closed.emplace_back(c.s0, c.s1);
      const LumenSegmentation s = SegmentColonLumen(phantom::SynthesizeCT(scan, o, none), SegmentationOptions{}, none);
      ASSERT_EQ(s.pieces.size(), closed.size() + 1);

      // Material s of every labelled voxel, per label value.
      const phantom::TubeLocator tube(scan, o.tissue.wallThicknessMm, 1.0);
      std::vector<std::vector<double>> sOf(s.pieces.size() + 1);
      for (std::size_t k = 0; k < s.label.size[2]; ++k)
        for (std::size_t j = 0; j < s.label.size[1]; ++j)
          for (std::size_t i = 0; i < s.label.size[0]; ++i) {
            const unsigned char v = s.label.At(i, j, k);
            if (!v) continue;
            ASSERT_LE(v, s.pieces.size());
            const phantom::TubeSample q = tube.Query(s.label.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k))));
            if (q.near) sOf[v].push_back(q.s);
          }
      std::size_t largest = 0;
      for (std::size_t k = 0; k < s.pieces.size(); ++k) {
        std::vector<double>& piece = sOf[static_cast<std::size_t>(s.pieces[k].labelValue)];
        ASSERT_FALSE(piece.empty());
        std::sort(piece.begin(), piece.end());
        // Inside the open stretch between collapse k-1 and collapse k (5th to 95th percentile).
        const double lo = piece[piece.size() / 20], hi = piece[piece.size() * 19 / 20];
        const double open0 = k == 0 ? 0.0 : closed[k - 1].second, open1 = k == closed.size() ? anatomy.length : closed[k].first;
        EXPECT_GE(lo, open0 - 2.0) << "piece " << k;
        EXPECT_LE(hi, open1 + 2.0) << "piece " << k;
        if (s.components[s.pieces[k].component].voxels > s.components[s.pieces[largest].component].voxels) largest = k;
      }
      EXPECT_EQ(s.pieces[largest].labelValue, 1);
      EXPECT_EQ(s.pieces[largest].component, s.colon);
    }
  }
}

TEST(PieceBridge, StraightBridgeFillsItsTubeOnly) {
  // Two ends facing each other across 40 mm along x: the curve is the straight segment and the
  // drawn voxels are the cylinder of radius 5 mm around it plus the two half-balls at its ends.
  const PieceEnd from = End(-20, 0, 0, 1, 0, 0), to = End(20, 0, 0, -1, 0, 0);
  const Bridge b = MakeBridge(from, to, 5.0);
  EXPECT_NEAR(b.LengthMm(), 40.0, 1e-6);
  for (const Eigen::Vector3d& p : b.curve) EXPECT_LT(std::hypot(p.y(), p.z()), 1e-9);
  Volume<unsigned char> m;
  m.size = {{81, 21, 21}};
  m.spacing = Eigen::Vector3d(0.5, 0.5, 0.5);
  m.origin = Eigen::Vector3d(-20, -5, -5);
  m.Allocate(0);
  m.At(40, 10, 10) = 7;  // an existing voxel is left as it is
  const std::size_t added = DrawBridge(b, m, 2);
  EXPECT_EQ(m.At(40, 10, 10), 7);
  const double expected = (M_PI * 25.0 * 40.0 + 0.0) / 0.125;  // the end balls lie outside the grid
  EXPECT_NEAR(double(added), expected, 0.05 * expected);
  for (std::size_t k = 0; k < 21; ++k)
    for (std::size_t j = 0; j < 21; ++j)
      for (std::size_t i = 0; i < 81; ++i) {
        const Eigen::Vector3d p = m.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
        if (m.At(i, j, k) == 2) EXPECT_LE(std::hypot(p.y(), p.z()), 5.0 + 1e-9);
      }
}

TEST(PieceBridge, CurvedBridgeLeavesAndEntersAlongTheEnds) {
  // A U-turn at the bottom of a loop: both pieces run out downwards (-z) at their ends, 60 mm
  // apart; the curve leaves downwards and comes back up into the second piece.
  const PieceEnd from = End(-30, 0, 0, 0, 0, -1), to = End(30, 0, 0, 0, 0, -1);
  const Bridge b = MakeBridge(from, to, 5.0);
  ASSERT_GE(b.curve.size(), 3u);
  const Eigen::Vector3d first = (b.curve[1] - b.curve[0]).normalized();
  const Eigen::Vector3d last = (b.curve.back() - b.curve[b.curve.size() - 2]).normalized();
  EXPECT_GT(first.dot(Eigen::Vector3d(0, 0, -1)), 0.99);
  EXPECT_GT(last.dot(Eigen::Vector3d(0, 0, 1)), 0.99);
  double lowest = 0.0;
  for (const Eigen::Vector3d& p : b.curve) lowest = std::min(lowest, p.z());
  EXPECT_LT(lowest, -10.0);
  EXPECT_GT(b.LengthMm(), 60.0);
}
