// CT of a closed mesh against the partial-volume model computed independently (exact distance
// to the mesh through VTK's locator, inside/outside from the analytic shape), and tagged fluid.
#include "Phantom/SynthesizeCT.h"
#include "RealColon/MeshCT.h"
#include "Surface/SurfaceDistance.h"
#include "TestShapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace colonmap::realcolon {
namespace {

struct Capsule {
  Eigen::Vector3d a{0, 0, -10}, b{0, 0, 10};
  double r = 12.0;
  double Distance(const Eigen::Vector3d& p) const {  // signed: negative inside
    const double t = std::clamp((p - a).dot(b - a) / (b - a).squaredNorm(), 0.0, 1.0);
    return (a + t * (b - a) - p).norm() - r;
  }
};

phantom::PhantomOptions Options() {
  phantom::PhantomOptions o;
  o.spacing = Eigen::Vector3d(1.0, 1.0, 1.0);
  o.tissue.noiseSigmaHU = 0.0;
  o.tissue.fieldOfViewMm = Eigen::Vector3d(48, 48, 60);
  o.tissue.fieldOfViewCentre = Eigen::Vector3d(0.3, -0.2, 0.1);  // voxel centres off the shape's symmetry
  o.tissue.bodySemiAxisXMm = 60.0;
  o.tissue.bodySemiAxisYMm = 50.0;
  return o;
}

TEST(MeshCT, PartialVolumeMatchesTheExactDistanceToTheMesh) {
  const Capsule cap;
  Eigen::MatrixXd line(2, 3);
  line.row(0) = cap.a.transpose();
  line.row(1) = cap.b.transpose();
  const TriangleMesh lumen = testing::TubeAround(line, cap.r, 0.4);
  phantom::PhantomOptions o = Options();
  o.fluid = false;
  Volume<short> ct = phantom::CTGrid(o);
  MeshScan scan;
  scan.lumen = &lumen;
  NullProgress np;
  SynthesizeMeshCT(scan, o, ct, np);
  // Expected values at every voxel within 6 mm of the wall.
  std::vector<Eigen::Vector3d> pts;
  std::vector<std::size_t> where;
  for (std::size_t k = 0; k < ct.size[2]; ++k)
    for (std::size_t j = 0; j < ct.size[1]; ++j)
      for (std::size_t i = 0; i < ct.size[0]; ++i) {
        const Eigen::Vector3d p = ct.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
        if (std::fabs(cap.Distance(p)) < 6.0) pts.push_back(p), where.push_back(ct.Offset(i, j, k));
      }
  Eigen::MatrixXd Q(static_cast<Eigen::Index>(pts.size()), 3);
  for (std::size_t q = 0; q < pts.size(); ++q) Q.row(static_cast<Eigen::Index>(q)) = pts[q].transpose();
  const surface::ClosestPoints cp = surface::ClosestOnSurface(lumen.V, lumen.F, Q);
  const double W = phantom::PartialVolumeHalfWidth(o);
  const phantom::TissueModel& t = o.tissue;
  int compared = 0, off = 0;
  for (std::size_t q = 0; q < pts.size(); ++q) {
    const double exact = cap.Distance(pts[q]);
    if (std::fabs(exact) < 0.1) continue;  // the mesh's own side of a point this close is unsure
    const double d = exact < 0 ? -cp.distance(static_cast<Eigen::Index>(q)) : cp.distance(static_cast<Eigen::Index>(q));
    const double a = phantom::PartialVolumeStep(d, W), b = std::min(a, phantom::PartialVolumeStep(d - t.wallThicknessMm, W));
    const double expected = (1 - a) * t.airHU + (a - b) * t.wallHU + b * phantom::BodyHU(pts[q], t, W);
    ++compared;
    if (std::fabs(ct.voxels[where[q]] - expected) > 1.0) ++off;
  }
  EXPECT_GT(compared, 10000);
  EXPECT_EQ(off, 0);
  // Deep inside: air; far outside the wall: fat.
  EXPECT_EQ(ct.At(24, 24, 30), -1000);
  EXPECT_EQ(ct.At(24, 24, 2), -100);
}

TEST(MeshCT, APoolFillsTheLumenBelowItsLevel) {
  const Capsule cap;
  Eigen::MatrixXd line(2, 3);
  line.row(0) = cap.a.transpose();
  line.row(1) = cap.b.transpose();
  const TriangleMesh lumen = testing::TubeAround(line, cap.r, 0.4);
  phantom::PhantomOptions o = Options();
  Volume<short> ct = phantom::CTGrid(o);
  MeshScan scan;
  scan.lumen = &lumen;
  scan.down = Eigen::Vector3d(0, 1, 0);  // supine: posterior (+y) is down
  scan.fluidHU = 800.0;
  scan.pools.push_back({Eigen::Vector3d(0, 10, 0), -4.0});  // level at y = 4
  NullProgress np;
  SynthesizeMeshCT(scan, o, ct, np);
  const double W = phantom::PartialVolumeHalfWidth(o);
  int fluid = 0, air = 0, wrong = 0;
  for (std::size_t k = 0; k < ct.size[2]; ++k)
    for (std::size_t j = 0; j < ct.size[1]; ++j)
      for (std::size_t i = 0; i < ct.size[0]; ++i) {
        const Eigen::Vector3d p = ct.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
        if (cap.Distance(p) > -1.5) continue;  // clear of the wall's partial volume
        const short v = ct.At(i, j, k);
        if (p.y() > 4.0 + W) (v == 800 ? ++fluid : ++wrong);
        else if (p.y() < 4.0 - W) (v == -1000 ? ++air : ++wrong);
      }
  EXPECT_GT(fluid, 500);
  EXPECT_GT(air, 2000);
  EXPECT_EQ(wrong, 0);
}

}  // namespace
}  // namespace colonmap::realcolon
