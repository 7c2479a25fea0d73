// The real segments of the Edinburgh Gut Cell Atlas model EdinGCA_3D_00020 (credit "Edinburgh
// Gut Cell Atlas, EdinGCA_3D_00020"; legacy .vtk in voxel units, scaled here by the voxel size
// 0.808594 x 0.808594 x 0.7 mm). Each is cleaned into a cylinder where possible and flattened
// with a shortest edge path between its two end loops as the cut: zero flips, mean |mu| <= 0.02.
// Cleaning: vtkCleanPolyData welds coincident points; faces on non-manifold edges are removed;
// non-manifold vertices are split; the largest component is kept. Segments that are still not
// cylinders (handles, caps, extra holes) are listed and skipped.
#include "Flattening/BeltramiCoefficient.h"
#include "Flattening/ConformalFlattening.h"
#include "Flattening/MidpointSubdivision.h"
#include "Flattening/PrepareSegment.h"
#include "Flattening/ShortestCutPath.h"
#include "IO/MeshIO.h"
#include "Surface/MeshTopology.h"
#include "Surface/VtkConversion.h"

#include <gtest/gtest.h>
#include <vtkCleanPolyData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <set>

namespace {

using namespace colonmap;
using namespace colonmap::flattening;

TriangleMesh CleanIntoCylinderCandidate(TriangleMesh m) {
  const Eigen::RowVector3d voxel(0.808594, 0.808594, 0.7);
  m.V = m.V.array().rowwise() * voxel.array();
  vtkNew<vtkPolyData> pd;
  surface::ToPolyData(m, pd);
  vtkNew<vtkCleanPolyData> clean;
  clean->SetInputData(pd);
  clean->PointMergingOn();
  clean->SetTolerance(0.0);
  clean->Update();
  TriangleMesh w = surface::FromPolyData(clean->GetOutput());
  // Faces on non-manifold edges out, then split touching fans, then the largest component.
  std::set<std::pair<int, int>> bad;
  for (const auto& e : surface::NonManifoldEdges(w.F)) bad.insert({e[0], e[1]});
  std::vector<bool> keep(w.F.rows(), true);
  for (Eigen::Index f = 0; f < w.F.rows(); ++f)
    for (int c = 0; c < 3; ++c) {
      const int a = w.F(f, c), b = w.F(f, (c + 1) % 3);
      if (bad.count({std::min(a, b), std::max(a, b)})) keep[f] = false;
    }
  TriangleMesh k;
  surface::KeepFaces(w.V, w.F, keep, k.V, k.F);
  surface::SplitNonManifoldVertices(k.V, k.F);
  const std::vector<int> comp = surface::FaceComponents(k.F);
  std::vector<bool> largest(k.F.rows());
  for (Eigen::Index f = 0; f < k.F.rows(); ++f) largest[f] = comp[f] == 0;
  TriangleMesh out;
  surface::KeepFaces(k.V, k.F, largest, out.V, out.F);
  return out;
}

// The criterion (zero flips, mean |mu| <= 0.02) on these coarse atlas meshes (1-19K faces,
// mean edge 3.0-3.6 mm, many obtuse triangles): as delivered, zero flips on all five cylinders
// since the intrinsic Delaunay Laplacian and conjugate-flux ends (before: 3, 11, 0, 12, 0) but
// mean |mu| 0.035-0.106: the map is piecewise linear, and its |mu| falls in proportion to the
// edge length. So each piece is also midpoint subdivided (MidpointSubdivision.h: the same
// surface, edges halved), level by level up to 3, until the target is met. Measured: |mu|
// falls by 0.42-0.51 per level; the target is met at level 1 (DSJ-SF-, 0.0181), 2 (ICVc-AO
// 0.0101, SF--SF 0.0149, SF-SF+ 0.0182) and 3 (HF-HF+, the short wide flexure piece: 0.0214 at
// level 2, 0.0110 at 3); no flips at any of these levels. (Level 3 of SF--SF, not needed, has 9
// flipped faces among the atlas's degenerate slivers, |mu| max 1.)
TEST(FlatteningGca, RealCylinderSegmentsFlattenWithoutFlipsAndReachMeanMuBelow002WhenSubdivided) {
  const std::filesystem::path dir = COLONMAP_GCA_SEGMENTS;
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "no GCA data at " << dir;
  std::vector<std::filesystem::path> files;
  for (const auto& e : std::filesystem::directory_iterator(dir))
    if (e.path().extension() == ".vtk") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  int flattened = 0;
  for (const auto& file : files) {
    const TriangleMesh m = CleanIntoCylinderCandidate(io::ReadMesh(file.string(), "GCA segment"));
    const surface::TopologyReport t = surface::AnalyzeTopology(m.F);
    if (t.euler != 0 || t.boundaryLoops != 2 || t.components != 1 || t.nonManifoldEdges || t.nonManifoldVertices) {
      std::printf("%s: not a cylinder after cleaning, skipped: %s\n", file.filename().c_str(), t.Summary().c_str());
      continue;
    }
    const auto loops = surface::BoundaryLoops(m.F);
    const Eigen::VectorXi cut = ShortestCutPath(m.V, m.F, loops[0], loops[1]);
    double previous = 0.0;
    for (int levels = 0; levels <= 3; ++levels) {
      const auto t0 = std::chrono::steady_clock::now();
      Eigen::VectorXi path = cut;
      TriangleMesh prepared = m;
      MidpointSubdivision(prepared, &path, levels);
      PrepareSegment(prepared, path);  // as ColonFlattening
      NullProgress np;
      const FlatteningResult f = ConformalFlattening(prepared.V, prepared.F, path, Eigen::VectorXd(), FlatteningOptions{}, np);
      const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
      const DistortionStats s = SummarizeDistortion(f.cut.V, f.uv, f.cut.F, BeltramiCoefficient(f.cut.V, f.uv, f.cut.F));
      std::printf("%s, %d subdivision(s): %ld faces, flips %ld, |mu| mean %.4f p99 %.4f max %.4f, %.1f x %.1f mm, %.3f s\n",
                  file.filename().c_str(), levels, s.faces, s.flipped, s.muMean, s.muP99, s.muMax, f.circumferenceMm,
                  f.lengthMm, seconds);
      EXPECT_EQ(s.flipped, 0) << file << ", " << levels << " subdivision(s)";
      if (levels == 0) EXPECT_LE(s.muMean, 0.12) << file;  // as delivered: 0.035-0.106 measured
      else EXPECT_LE(s.muMean, 0.6 * previous) << file << ": |mu| should halve per level, " << levels;
      previous = s.muMean;
      if (s.muMean <= 0.02) break;
    }
    EXPECT_LE(previous, 0.02) << file << ": not reached at 3 subdivisions";
    ++flattened;
  }
  // HF-HF+, DSJ-SF-, ICVc-AO and SF-SF+ are cylinders as delivered.
  EXPECT_GE(flattened, 4);
}

}  // namespace
