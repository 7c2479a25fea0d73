// Surface reconstruction on the phantom at coarse spacing, against its exact true wall.
#include "Surface/MeanCurvature.h"
#include "Core/RecordingProgress.h"
#include "Surface/SurfaceReconstruction.h"
#include "SurfaceDistance.h"

#include "Core/Error.h"
#include "IO/MeshIO.h"
#include "Phantom/Phantom.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

namespace colonmap::surface {
namespace {

using namespace colonmap::phantom;

constexpr double kSpacing = 1.5;
constexpr double kEndExclusionMm = 6.0;  // the truth is an open tube, our lumen has end caps

struct Phantom {
  PhantomOptions options;
  std::unique_ptr<ScanGeometry> scan;
  TriangleMesh truth;
  Eigen::VectorXd truthH;
  double length = 0.0;
  Volume<short> ct;
  Volume<float> label;
};

std::unique_ptr<Phantom> MakePhantom(const Eigen::Vector3d& spacing, bool withImages, std::uint32_t seed = 0,
                                     Posture posture = Posture::Supine) {
    auto q = std::make_unique<Phantom>();
    q->options.spacing = spacing;
    q->options.fluid = false;
    if (seed > 0) q->options.seed = seed;
    const ColonAnatomy anatomy = MakeAnatomy(q->options);
    q->scan = std::make_unique<ScanGeometry>(MakeScan(anatomy, posture, q->options));
    q->truth = TrueWall(*q->scan, q->options);
    q->truthH = MeanCurvature(q->truth.V, q->truth.F);
    q->length = q->truth.pointData.at("MaterialS").values.maxCoeff();
    if (!withImages) return q;
    NullProgress np;
    q->ct = SynthesizeCT(*q->scan, q->options, np);
    const Volume<unsigned char> lumen = LumenLabel(*q->scan, q->options, np);
    q->label.size = lumen.size;
    q->label.spacing = lumen.spacing;
    q->label.origin = lumen.origin;
    q->label.direction = lumen.direction;
    q->label.voxels.assign(lumen.voxels.begin(), lumen.voxels.end());
    return q;
}

const Phantom& Shared() {
  static const std::unique_ptr<Phantom> p = MakePhantom(Eigen::Vector3d::Constant(kSpacing), true);
  return *p;
}

struct Accuracy {
  double mean = 0, p95 = 0, max = 0;
  double inwardFraction = 0;     // vertex normals pointing towards the true centreline
  double curvatureCorrelation = 0;
};

// Symmetric surface distance (mean and 95th percentile over both directions' samples), away
// from the two ends of the truth tube.
Accuracy Measure(const Phantom& p, const TriangleMesh& mesh) {
  const Eigen::MatrixXd& sTruth = p.truth.pointData.at("MaterialS").values;
  auto sOfCell = [&](long cell) {
    return (sTruth(p.truth.F(cell, 0)) + sTruth(p.truth.F(cell, 1)) + sTruth(p.truth.F(cell, 2))) / 3.0;
  };
  auto inner = [&](double s) { return s > kEndExclusionMm && s < p.length - kEndExclusionMm; };
  std::vector<double> d;
  const testing::ClosestPoints toTruth = testing::ClosestOnSurface(p.truth.V, p.truth.F, mesh.V);
  const Eigen::MatrixXd N = VertexNormals(mesh.V, mesh.F);
  const Eigen::VectorXd& H = mesh.pointData.at("MeanCurvature").values;
  long inward = 0, counted = 0;
  std::vector<double> hOurs, hTruth;
  for (Eigen::Index v = 0; v < mesh.V.rows(); ++v) {
    const long cell = toTruth.cell[std::size_t(v)];
    const double s = sOfCell(cell);
    if (!inner(s)) continue;
    d.push_back(toTruth.distance(v));
    ++counted;
    if (N.row(v).dot(p.scan->CenterPoint(s).transpose() - mesh.V.row(v)) > 0) ++inward;
    hOurs.push_back(H(v));
    hTruth.push_back(p.truthH(p.truth.F(cell, 0)));
  }
  const testing::ClosestPoints toOurs = testing::ClosestOnSurface(mesh.V, mesh.F, p.truth.V);
  for (Eigen::Index v = 0; v < p.truth.V.rows(); ++v)
    if (inner(sTruth(v))) d.push_back(toOurs.distance(v));
  Accuracy a;
  for (double x : d) a.mean += x / double(d.size());
  a.p95 = testing::Percentile(d, 0.95);
  a.max = testing::Percentile(d, 1.0);
  a.inwardFraction = double(inward) / double(counted);
  const Eigen::Map<Eigen::VectorXd> x(hOurs.data(), long(hOurs.size())), y(hTruth.data(), long(hTruth.size()));
  const Eigen::VectorXd xc = x.array() - x.mean(), yc = y.array() - y.mean();
  a.curvatureCorrelation = xc.dot(yc) / (xc.norm() * yc.norm());
  return a;
}

double SignedVolume(const TriangleMesh& m) {
  double v = 0;
  for (Eigen::Index f = 0; f < m.F.rows(); ++f) {
    const Eigen::Vector3d a = m.V.row(m.F(f, 0)), b = m.V.row(m.F(f, 1)), c = m.V.row(m.F(f, 2));
    v += a.dot(b.cross(c));
  }
  return v / 6;
}

void ExpectGoodSurface(const SurfaceResult& r, long target) {
  EXPECT_TRUE(r.topology.IsClosedGenusZero()) << r.topology.Summary();
  EXPECT_EQ(r.topology.euler, 2);
  EXPECT_EQ(r.topology.components, 1);
  EXPECT_EQ(r.topology.nonManifoldEdges, 0);
  EXPECT_EQ(r.topology.inconsistentEdges, 0);
  EXPECT_NEAR(double(r.mesh.F.rows()), double(target), 0.05 * target);
  EXPECT_LT(SignedVolume(r.mesh), 0.0);  // faces oriented into the lumen
}

TEST(SurfaceReconstruction, LabelAndCTMatchTheTrueWall) {
  const Phantom& p = Shared();
  SurfaceOptions o;
  o.targetFaces = 60000;
  NullProgress np;
  const auto t0 = std::chrono::steady_clock::now();
  const SurfaceResult r = ReconstructSurface(p.label, &p.ct, o, np);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  ExpectGoodSurface(r, o.targetFaces);
  EXPECT_TRUE(r.usedCT);
  EXPECT_EQ(r.contourPasses, 1);  // manifold by construction: no second pass with a CT
  const Accuracy a = Measure(p, r.mesh);
  std::printf("label+CT at %.1f mm: %ld contour faces -> %ld, %.2f s, distance mean %.3f p95 %.3f max %.3f mm, "
              "inward normals %.4f, curvature correlation %.3f\n",
              kSpacing, r.contourFaces, long(r.mesh.F.rows()), seconds, a.mean, a.p95, a.max, a.inwardFraction,
              a.curvatureCorrelation);
  // Bounds in units of the spacing. Measured at 1.5 mm: mean about 0.03 h, p95 about 0.11 h.
  // The clinical targets (0.3 and 1.0 mm at 0.7 mm) are 0.43 h and 1.4 h.
  EXPECT_LT(a.mean, 0.1 * kSpacing);
  EXPECT_LT(a.p95, 0.3 * kSpacing);
  EXPECT_GT(a.inwardFraction, 0.99);
  // Our vertex curvature against the cotangent curvature of the true wall at the closest point.
  EXPECT_GT(a.curvatureCorrelation, 0.6);
}

TEST(SurfaceReconstruction, LabelOnlyIsClosedAndCloseToTheWall) {
  const Phantom& p = Shared();
  SurfaceOptions o;
  o.targetFaces = 40000;
  NullProgress np;
  const SurfaceResult r = ReconstructSurface(p.label, nullptr, o, np);
  ExpectGoodSurface(r, o.targetFaces);
  EXPECT_FALSE(r.usedCT);
  const Accuracy a = Measure(p, r.mesh);
  std::printf("label only at %.1f mm: %ld faces, distance mean %.3f p95 %.3f max %.3f mm, inward %.4f, "
              "curvature correlation %.3f\n",
              kSpacing, long(r.mesh.F.rows()), a.mean, a.p95, a.max, a.inwardFraction, a.curvatureCorrelation);
  // Without the CT the wall is only known to the voxel: measured mean about 0.1 h, p95 0.3 h.
  EXPECT_LT(a.mean, 0.2 * kSpacing);
  EXPECT_LT(a.p95, 0.5 * kSpacing);
  EXPECT_GT(a.inwardFraction, 0.99);
  EXPECT_GT(a.curvatureCorrelation, 0.5);
}

TEST(SurfaceReconstruction, HonoursDirectionAndLabelValue) {
  const Phantom& p = Shared();
  SurfaceOptions o;
  o.targetFaces = 20000;
  NullProgress np;
  const SurfaceResult base = ReconstructSurface(p.label, nullptr, o, np);
  // Same voxels under an oblique, reflected direction and another label value.
  Volume<float> turned = p.label;
  turned.direction = Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix() *
                     Eigen::Vector3d(1, -1, 1).asDiagonal();
  for (float& v : turned.voxels) v = v > 0 ? 7.0f : 2.0f;
  o.labelValue = 7;
  const SurfaceResult r = ReconstructSurface(turned, nullptr, o, np);
  ASSERT_EQ(r.mesh.V.rows(), base.mesh.V.rows());
  double worst = 0;
  for (Eigen::Index v = 0; v < r.mesh.V.rows(); ++v) {
    const Eigen::Vector3d q = p.label.origin + turned.direction * (base.mesh.V.row(v).transpose() - p.label.origin);
    worst = std::max(worst, (q - r.mesh.V.row(v).transpose()).norm());
  }
  EXPECT_LT(worst, 1e-6);
  EXPECT_LT(SignedVolume(r.mesh), 0.0);
  EXPECT_TRUE(r.topology.IsClosedGenusZero());
}

TEST(SurfaceReconstruction, DeterministicAndReportsDroppedComponents) {
  // A cube of lumen plus a small separate blob: the blob is dropped and reported.
  Volume<float> label;
  label.size = {{30, 30, 30}};
  label.spacing = Eigen::Vector3d(1.0, 1.0, 2.0);
  label.Allocate(0.0f);
  for (std::size_t k = 5; k < 20; ++k)
    for (std::size_t j = 5; j < 25; ++j)
      for (std::size_t i = 5; i < 25; ++i) label.At(i, j, k) = 1.0f;
  for (std::size_t k = 24; k < 27; ++k)
    for (std::size_t j = 2; j < 5; ++j)
      for (std::size_t i = 2; i < 5; ++i) label.At(i, j, k) = 1.0f;
  // The main block touches the image border: the crop pads it, so it still closes.
  for (std::size_t k = 0; k < 5; ++k) label.At(15, 15, k) = label.At(16, 15, k) = 1.0f;
  SurfaceOptions o;
  o.targetFaces = 2000;
  NullProgress np;
  const SurfaceResult a = ReconstructSurface(label, nullptr, o, np);
  const SurfaceResult b = ReconstructSurface(label, nullptr, o, np);
  EXPECT_EQ(a.mesh.V, b.mesh.V);
  EXPECT_EQ(a.mesh.F, b.mesh.F);
  // From the lumen's mask (ColonSurface's path): the same surface. Another label value is
  // not the lumen.
  const SurfaceResult fromMask = ReconstructSurfaceFromMask(LumenMask(label, 1.0), nullptr, o, np);
  EXPECT_EQ(fromMask.mesh.V, a.mesh.V);
  EXPECT_EQ(fromMask.mesh.F, a.mesh.F);
  EXPECT_EQ(fromMask.lumenVoxels, a.lumenVoxels);
  const Volume<unsigned char> other = LumenMask(label, 2.0);
  EXPECT_EQ(std::count(other.voxels.begin(), other.voxels.end(), 1), 0);
  ASSERT_EQ(a.droppedComponents.size(), 1u);
  EXPECT_GT(a.droppedComponents[0], 0);
  EXPECT_EQ(a.topology.boundaryLoops, 0);
  EXPECT_TRUE(a.topology.IsClosedGenusZero()) << a.topology.Summary();
}

TEST(SurfaceReconstruction, RejectsBadInput) {
  Volume<float> label;
  label.size = {{8, 8, 8}};
  label.Allocate(0.0f);
  SurfaceOptions o;
  NullProgress np;
  EXPECT_THROW(ReconstructSurface(label, nullptr, o, np), Error);  // empty
  label.At(4, 4, 4) = 2.0f;
  EXPECT_THROW(ReconstructSurface(label, nullptr, o, np), Error);  // value 1 not present
  label.At(4, 4, 4) = 1.0f;
  Volume<short> ct;
  ct.size = {{8, 8, 9}};
  ct.Allocate(0);
  EXPECT_THROW(ReconstructSurface(label, &ct, o, np), Error);  // other grid
}

TEST(SurfaceReconstruction, Cancels) {
  const Phantom& p = Shared();
  for (int n : {0, 3, 6, 9}) {
    RecordingProgress c(n + 1);  // Cancel after n reports
    EXPECT_THROW(ReconstructSurface(p.label, &p.ct, SurfaceOptions(), c), Cancelled);
  }
}

// Benchmark helper, not run by ctest: measures a surface file made by the ColonSurface module from
// a phantom scan (default the seed-1 supine one, as ColonSurfaceMakeTestData makes) against the
// true wall.
//   COLONMAP_SURFACE_EVAL=surface.vtp COLONMAP_SURFACE_SPACING=0.7,0.7,1.0
//   [COLONMAP_SURFACE_SEED=N] [COLONMAP_SURFACE_POSTURE=prone]
//   ColonMapSurfaceTests --gtest_also_run_disabled_tests --gtest_filter=*DISABLED_Evaluate*
TEST(SurfaceReconstruction, DISABLED_EvaluateFile) {
  const char* file = std::getenv("COLONMAP_SURFACE_EVAL");
  const char* spacing = std::getenv("COLONMAP_SURFACE_SPACING");
  ASSERT_TRUE(file && spacing);
  double h[3];
  ASSERT_EQ(std::sscanf(spacing, "%lf,%lf,%lf", &h[0], &h[1], &h[2]), 3);
  const char* seed = std::getenv("COLONMAP_SURFACE_SEED");
  const char* posture = std::getenv("COLONMAP_SURFACE_POSTURE");
  const auto p = MakePhantom(Eigen::Vector3d(h[0], h[1], h[2]), false, seed ? static_cast<std::uint32_t>(std::atoi(seed)) : 0,
                             posture && std::string(posture) == "prone" ? Posture::Prone : Posture::Supine);
  const TriangleMesh mesh = io::ReadMesh(file, "surface");
  const Accuracy a = Measure(*p, mesh);
  const TopologyReport t = AnalyzeTopology(mesh.F);
  std::printf("%s: %s\ndistance mean %.3f p95 %.3f max %.3f mm, inward normals %.4f, curvature correlation %.3f\n",
              file, t.Summary().c_str(), a.mean, a.p95, a.max, a.inwardFraction, a.curvatureCorrelation);
}

}  // namespace
}  // namespace colonmap::surface
