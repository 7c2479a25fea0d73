// Ground-truth pairs from the three real colons in ../shared/data (issue 17), seeds 1-8 each:
// valid pairs (both surfaces embedded, same connectivity, material s monotone along the tube),
// consistent truth (the prone evaluation point is the image of the supine one, on the same face
// with the same barycentric coordinates), the deformation model's bounds (local stretch, no
// registration baseline), and determinism.
#include "RealColon/RealColonPhantom.h"
#include "Core/Error.h"
#include "IO/MarkupsIO.h"
#include "IO/MeshIO.h"
#include "Phantom/Phantom.h"
#include "Surface/MeshTopology.h"
#include "Surface/SelfIntersection.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <string>

namespace colonmap::realcolon {
namespace {

const std::string kData = std::string(COLONMAP_SHARED_DIR) + "/data/";

// The source is read and welded once per atlas.
const ColonSource& Source(const std::string& atlas) {
  static std::map<std::string, std::unique_ptr<ColonSource>> cache;
  auto& s = cache[atlas];
  if (!s) s = std::make_unique<ColonSource>(ReadColonSource(kData + atlas));
  return *s;
}

RealColonPair Make(const std::string& atlas, std::uint32_t seed) {
  RealColonOptions o;
  o.phantom.seed = seed;
  NullProgress np;
  return MakeRealColonPair(Source(atlas), o, np);
}

Eigen::Vector3d Barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d n = (b - a).cross(c - a);
  const double area = n.squaredNorm();
  const double u = (c - b).cross(p - b).dot(n) / area, v = (a - c).cross(p - c).dot(n) / area;
  return Eigen::Vector3d(u, v, 1.0 - u - v);
}

class RealColonPairs : public ::testing::TestWithParam<std::tuple<std::string, int>> {};

TEST_P(RealColonPairs, AreValidConsistentAndWithinTheDeformationModel) {
  const auto [atlas, seed] = GetParam();
  const RealColonPair p = Make(atlas, static_cast<std::uint32_t>(seed));
  const TubeMaterial& m = p.material;
  std::printf("%s seed %d: %.0f mm, no registration %.1f mm mean (A %.1f T %.1f D %.1f S %.1f R %.1f), local stretch %.3f, "
              "%zu polyps, harmonic extrema %ld\n",
              atlas.c_str(), seed, m.length, p.displacement.mean, p.displacementBySegment[0].mean, p.displacementBySegment[1].mean,
              p.displacementBySegment[2].mean, p.displacementBySegment[3].mean, p.displacementBySegment[4].mean,
              p.maxLocalStretch, p.polyps.size(), m.harmonicExtrema);

  // Embedded, same connectivity.
  EXPECT_EQ(surface::FindSelfIntersections(p.supine.closed.V, p.supine.closed.F).pairs, 0);
  EXPECT_EQ(surface::FindSelfIntersections(p.prone.closed.V, p.prone.closed.F).pairs, 0);
  ASSERT_TRUE(p.supine.wall.F == p.prone.wall.F);
  ASSERT_EQ(p.supine.wall.V.rows(), p.prone.wall.V.rows());

  // s monotone along the tube: every level set one loop, no local extremum.
  EXPECT_EQ(m.localExtrema, 0);
  EXPECT_EQ(m.maxCurvesPerLevel, 1);
  const Eigen::MatrixXd& s = p.supine.wall.pointData.at("MaterialS").values;
  EXPECT_GE(s.minCoeff(), 0.0);
  EXPECT_LE(s.maxCoeff(), m.length + 1e-9);
  const Eigen::MatrixXd& seg = p.supine.wall.pointData.at("SegmentId").values;
  for (Eigen::Index v = 0; v < s.rows(); v += 97) EXPECT_EQ(seg(v, 0), p.SegmentOf(s(v, 0)));
  for (int k = 1; k < 4; ++k) EXPECT_GT(p.flexureS[k], p.flexureS[k - 1] + 30.0);

  // Truth consistency: each prone evaluation point is the supine one's image, same face, same
  // barycentric coordinates, on the prone wall.
  const MarkupList es = RealEvaluationMarkups(p, phantom::Posture::Supine), ep = RealEvaluationMarkups(p, phantom::Posture::Prone);
  ASSERT_EQ(es.points.size(), 200u);
  ASSERT_EQ(ep.points.size(), es.points.size());
  for (std::size_t i = 0; i < p.sites.size(); ++i) {
    const RealSite& e = p.sites[i];
    const auto corner = [&](const TriangleMesh& t, int c) { return Eigen::Vector3d(t.V.row(t.F(e.face, c)).transpose()); };
    const Eigen::Vector3d bs = Barycentric(es.points[i].position, corner(p.supine.closed, 0), corner(p.supine.closed, 1), corner(p.supine.closed, 2));
    const Eigen::Vector3d bp = Barycentric(ep.points[i].position, corner(p.prone.closed, 0), corner(p.prone.closed, 1), corner(p.prone.closed, 2));
    EXPECT_LT((bs - bp).cwiseAbs().maxCoeff(), 1e-6);
    EXPECT_GE(bs.minCoeff(), -1e-9);
    EXPECT_EQ(es.points[i].label, ep.points[i].label);
  }
  const MarkupList ps = RealPolypMarkups(p, phantom::Posture::Supine);
  EXPECT_GE(ps.points.size(), 2u);

  // The deformation model: local stretch within +-15%; no registration 8-15 mm mean give or
  // take, the mobile transverse and sigmoid above the fixed segments.
  EXPECT_LE(p.maxLocalStretch, 0.15);
  EXPECT_GT(p.displacement.mean, 7.0);
  EXPECT_LT(p.displacement.mean, 20.0);
  const double fixed = std::max({p.displacementBySegment[0].mean, p.displacementBySegment[4].mean});
  EXPECT_GT(p.displacementBySegment[1].mean, fixed);
  EXPECT_GT(p.displacementBySegment[3].mean, fixed);
  EXPECT_LT(p.dilatation.all.max, 1e6);  // no degenerate image face
}

INSTANTIATE_TEST_SUITE_P(Atlases, RealColonPairs,
                         ::testing::Combine(::testing::Values("gca-00020", "hubmap-vhm-00070", "hubmap-vhf-00080"),
                                            ::testing::Range(1, 9)),
                         [](const auto& info) {
                           std::string name = std::get<0>(info.param) + "_seed" + std::to_string(std::get<1>(info.param));
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

TEST(RealColonPair, WithoutDeformationTheProneScanIsTheSupineScan) {
  RealColonOptions o;
  o.phantom.deformation = 0.0;
  NullProgress np;
  const RealColonPair p = MakeRealColonPair(Source("hubmap-vhf-00080"), o, np);
  EXPECT_LT((p.prone.closed.V - p.supine.closed.V).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT(p.displacement.max, 1e-9);
  EXPECT_NEAR(p.dilatation.all.max, 1.0, 1e-9);
}

TEST(RealColonPair, IsTheSameOnASecondRun) {
  const RealColonPair a = Make("hubmap-vhf-00080", 3), b = Make("hubmap-vhf-00080", 3);
  EXPECT_TRUE(a.prone.closed.V == b.prone.closed.V);
  EXPECT_TRUE(a.supine.wall.V == b.supine.wall.V);
  EXPECT_EQ(a.sites.size(), b.sites.size());
}

// The atlas weld (Analysis/GcaModel.h) on the HuBMAP male colon, whose pieces' seams merge within
// the tolerance: with VTK 9.1's threaded merge it came out in 4 forms in 6 runs; now the same.
TEST(ColonSource, TheWeldIsTheSameOnEveryRun) {
  const ColonSource first = ReadColonSource(kData + "hubmap-vhm-00070");
  for (int run = 0; run < 3; ++run) {
    const ColonSource again = ReadColonSource(kData + "hubmap-vhm-00070");
    ASSERT_EQ(again.surface.V.rows(), first.surface.V.rows()) << "run " << run;
    ASSERT_EQ(again.surface.F.rows(), first.surface.F.rows()) << "run " << run;
    ASSERT_TRUE(again.surface.V == first.surface.V) << "run " << run;
    ASSERT_TRUE(again.surface.F == first.surface.F) << "run " << run;
  }
}

// A folder of one's own (lumen.vtp, midline.mrk.json, flexures.mrk.json), made from the tube
// phantom, whose material s and flexures are known exactly: the real-colon generator must find
// the tube's flexures where the tube has them.
TEST(RealColonPair, FromAFolderOfOnesOwnFindsTheFlexuresWhereTheyAre) {
  phantom::PhantomOptions po;
  po.seed = 4;
  po.meshPointsAround = 96;
  const phantom::ColonAnatomy anatomy = phantom::MakeAnatomy(po);
  const phantom::ScanGeometry scan = phantom::MakeScan(anatomy, phantom::Posture::Supine, po);
  TriangleMesh wall = phantom::TrueWall(scan, po);
  wall.pointData.clear();
  // Close both ends with a fan around each loop's centroid.
  const auto loops = surface::BoundaryLoops(wall.F);
  ASSERT_EQ(loops.size(), 2u);
  Eigen::MatrixXd V(wall.V.rows() + 2, 3);
  V.topRows(wall.V.rows()) = wall.V;
  Eigen::MatrixXi F(wall.F.rows() + static_cast<Eigen::Index>(loops[0].size() + loops[1].size()), 3);
  F.topRows(wall.F.rows()) = wall.F;
  Eigen::Index f = wall.F.rows();
  for (std::size_t l = 0; l < 2; ++l) {
    const int c = static_cast<int>(wall.V.rows() + static_cast<Eigen::Index>(l));
    V.row(c) = Eigen::RowVector3d::Zero();
    for (int v : loops[l]) V.row(c) += wall.V.row(v) / static_cast<double>(loops[l].size());
    for (std::size_t i = 0; i < loops[l].size(); ++i) F.row(f++) << loops[l][(i + 1) % loops[l].size()], loops[l][i], c;
  }
  wall.V = V;
  wall.F = F;
  const std::string dir = ::testing::TempDir() + "/colonmap-own-colon";
  std::filesystem::create_directories(dir);
  io::WriteMesh(wall, dir + "/lumen.vtp", "lumen");
  io::WriteMarkups(phantom::ToMarkups(phantom::CenterlineSamples(scan, 2.0)), dir + "/midline.mrk.json", "midline");
  io::WriteMarkups(phantom::Flexures(scan), dir + "/flexures.mrk.json", "flexures");

  const ColonSource src = ReadColonSource(dir);
  RealColonOptions o;
  NullProgress np;
  const RealColonPair p = MakeRealColonPair(src, o, np);
  // Flexures at the tube's (as fractions of the length: our centreline cuts the bends a little).
  for (int k = 0; k < 4; ++k) {
    const double ours = p.flexureS[static_cast<std::size_t>(k)] / p.material.length;
    const double truth = anatomy.flexureS[static_cast<std::size_t>(k)] / anatomy.length;
    std::printf("%s at %.4f of the length (tube %.4f)\n", phantom::FlexureName(k), ours, truth);
    EXPECT_NEAR(ours, truth, 0.015) << phantom::FlexureName(k);
  }
  std::printf("length %.1f mm (tube %.1f)\n", p.material.length, anatomy.length);
  EXPECT_NEAR(p.material.length, anatomy.length, 0.05 * anatomy.length);
  EXPECT_EQ(p.material.localExtrema, 0);
  EXPECT_EQ(p.material.maxCurvesPerLevel, 1);
  std::filesystem::remove_all(dir);
}

TEST(RealColonPair, AFolderWithoutTheFilesIsRefusedNamingIt) {
  try {
    ReadColonSource(kData + "totalseg-example-ct");
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("totalseg-example-ct"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("lumen.vtp"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace colonmap::realcolon
