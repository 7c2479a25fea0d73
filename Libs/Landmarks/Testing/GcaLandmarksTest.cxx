// The landmark stage on a real colon: the Edinburgh Gut Cell Atlas model EdinGCA_3D_00020
// (CC BY 4.0; credit "Edinburgh Gut Cell Atlas, EdinGCA_3D_00020"), ../shared/data/gca-00020.
// Its segmented surfaces are welded into one closed colon (Analysis/GcaModel: WeldGcaColon),
// FindLandmarks runs on it, and the found splenic flexure, hepatic flexure and descending-
// sigmoid junction are compared with the atlas's own landmarks, which are indices into its
// midline path: each found flexure is projected onto that path (nearest point) and its
// distance ALONG the path to the atlas landmark must be within 40 mm (issue 5). The GCA has no
// rectosigmoid landmark, so the RSJ is only printed.
//
// The atlas surfaces have handles (genus 6 once welded), so the welded colon is made genus 0 the
// pipeline's way (voxelised, topology-preserving growth, contour: GenusZeroGcaColon), at 1.5 mm
// and 200K faces, which is also the benchmark size (FindLandmarks under 5 s).
//
// Measured with issue 19's centreline (the along-colon function's level-set centroids, 5 mm
// smoothing): HF +38.7 mm, SF -7.5 mm, DSJ +28.5 mm (+23.3 mm since the DSJ's turn counts only
// where the descent has slowed, +12.0 mm since it counts only where the colon descends no steeper
// than 10 degrees); centreline 2254 mm, 4.2% shorter than the atlas midline. Before it (1.5 mm, 200K faces; Flexures.h rules on the level-set curve, carried to the centred
// centreline): HF +38.8 mm, SF -5.8 mm, DSJ +29.6 mm (2 mm grid: +34.8, -8.2, +30.8; before
// centring, 2 mm: +37.6, -10.5, +29.2). 1.5 mm because at 2 mm the handle cuts leave thin
// fingers that the flattening cannot map (Flattening/Testing/GcaFlatteningTest.cxx).
// Before (exit-angle walks): HF +311 mm (the walk from the cecum fired next to this caecum,
// whose pole runs horizontally for ~80 mm) and DSJ +512 mm (the walk from SF stopped where this
// tortuous descending colon first tilts 50 degrees off the vertical, 70 mm below the SF). The
// HF figure is also limited by the evaluation: before centring our centreline ran up to 17 mm
// from the atlas midline near the HF (mean clearance to the wall 11.7 mm against the midline's
// 15.9 mm, and 22% shorter; centred: 13% shorter, clearance 15.8 mm), and the nearest-point
// projection onto the wiggly midline jumps by 33 mm between centreline samples 6 mm apart there;
// the same HF rule run on the atlas midline itself lands within 5 mm of the atlas HF.
#include "Landmarks/ColonLandmarks.h"

#include "Analysis/GcaModel.h"
#include "Analysis/MidlineProjection.h"
#include "Surface/MeshTopology.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

namespace colonmap::landmarks {
namespace {

const std::string kGca = std::string(COLONMAP_SHARED_DIR) + "/data/gca-00020";

void PrintWeld(const analysis::GcaWeld& w) {
  std::printf("GCA weld (Edinburgh Gut Cell Atlas, EdinGCA_3D_00020):\n");
  for (const auto& s : w.steps)
    std::printf("  %-42s V %6ld F %6ld components %3d Euler %5ld loops %3d non-manifold edges %3ld vertices %3ld\n",
                s.step.c_str(), s.vertices, s.faces, s.components, s.euler, s.boundaryLoops, s.nonManifoldEdges,
                s.nonManifoldVertices);
  std::printf("  degenerate faces %ld, duplicate faces %ld, faces on non-manifold edges %ld, split vertices %d, "
              "faces of small components %ld, capped loops %d (edges:",
              w.degenerateFaces, w.duplicateFaces, w.nonManifoldFaces, w.splitVertices, w.droppedFaces, w.capVertices);
  for (int n : w.capLoopSizes) std::printf(" %d", n);
  std::printf(")\n");
}

// All three atlas flexures within 40 mm of the atlas landmarks along its midline.
void CheckGcaLandmarks() {
  if (!std::filesystem::is_directory(kGca)) GTEST_SKIP() << "no GCA data at " << kGca;
  const analysis::GcaModel g = analysis::ReadGcaModel(kGca);
  const analysis::GcaWeld w = analysis::WeldGcaColon(g);
  PrintWeld(w);
  // The weld joins the nine pieces into one closed, manifold, oriented surface (genus 6).
  const surface::TopologyReport wt = surface::AnalyzeTopology(w.colon.F);
  EXPECT_EQ(wt.components, 1);
  EXPECT_EQ(wt.boundaryLoops, 0);
  EXPECT_EQ(wt.nonManifoldEdges, 0);
  EXPECT_EQ(wt.inconsistentEdges, 0);
  const analysis::GcaGenusZero g0 = analysis::GenusZeroGcaColon(w, 1.5, 200000);
  std::printf("genus 0 (voxelised 1.5 mm, ReconstructSurface): %s; lumen %.0f ml, %ld handles cut (%zu voxels), "
              "cavity voxels filled %zu; distance to the weld mean %.2f p99 %.2f max %.2f mm, weld to it "
              "mean %.2f p99 %.2f max %.2f mm; %.1f s\n",
              surface::AnalyzeTopology(g0.colon.F).Summary().c_str(), g0.lumenMl, g0.handles, g0.handleVoxelsRemoved,
              g0.cavityVoxelsFilled, g0.toWeldMean, g0.toWeldP99, g0.toWeldMax, g0.fromWeldMean, g0.fromWeldP99,
              g0.fromWeldMax, g0.seconds);
  for (const std::string& note : g0.notes) std::printf("  %s\n", note.c_str());
  ASSERT_TRUE(surface::AnalyzeTopology(g0.colon.F).IsClosedGenusZero());
  EXPECT_LT(g0.toWeldMean, 0.5);  // the genus-0 surface stays on the atlas surface (1.5 mm grid)

  NullProgress np;
  const auto t0 = std::chrono::steady_clock::now();
  const LandmarkResult r = FindLandmarks(g0.colon, {}, np);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("FindLandmarks: %ld faces, %.2f s (", static_cast<long>(g0.colon.F.rows()), secs);
  for (const auto& [name, s] : r.times) std::printf(" %s %.2f", name.c_str(), s);
  std::printf(" ), centreline %.0f mm, GCA midline anus->AO %.0f mm; mean clearance to the wall %.1f mm (geodesic "
              "level-set curve %.1f mm)\n",
              r.centerline.Length(), g.Arc("AO"), r.centerline.clearanceMm, r.centerline.clearanceBeforeMm);
  // Issue 19: the centreline follows the tortuous colon (the along-colon function's level-set
  // centroids): within 5% of the atlas midline's length (measured 4.2% shorter; the geodesic
  // curve moved onto the medial line was 12% shorter).
  EXPECT_NEAR(r.centerline.Length(), g.Arc("AO"), 0.05 * g.Arc("AO"));

  // The atlas midline from the anus to the appendix orifice (the appendix is not in the colon).
  const Eigen::MatrixXd midline = g.midline.topRows(g.landmark.at("AO") + 1);
  analysis::ProjectionOptions po;
  po.excludeBeyondEnds = false;
  // Time (issue 5: 200K faces under 5 s) is printed above and benchmarked, not asserted: a test
  // that shares 2 cores with others measured 1.3-5.4 s.
  const char* atlasName[4] = {"HF", "SF", "DSJ", nullptr};
  for (int k = 0; k < 4; ++k) {
    const double found = analysis::ProjectToMidline(r.flexures.position[k].transpose(), midline, po).arc(0);
    if (!atlasName[k]) {
      std::printf("  %-3s at %.0f mm along the GCA midline from the anus (no atlas landmark)\n",
                  Flexures::Names()[k], found);
      continue;
    }
    const double truth = g.Arc(atlasName[k]);
    std::printf("  %-3s found at %.0f mm along the GCA midline, atlas %.0f mm: %+.1f mm\n", Flexures::Names()[k], found,
                truth, found - truth);
    EXPECT_LE(std::fabs(found - truth), 40.0) << Flexures::Names()[k];
  }
}

TEST(LandmarksGca, HepaticSplenicDescendingSigmoidWithin40MmOfTheAtlas) { CheckGcaLandmarks(); }

}  // namespace
}  // namespace colonmap::landmarks
