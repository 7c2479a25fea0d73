#include "SynthesizeCT.h"

#include "Random.h"
#include "TubeLocator.h"
#include "VoxelLoop.h"

#include <algorithm>
#include <cmath>

namespace colonmap {
namespace phantom {
namespace {

// Signed distance to an axis-aligned ellipse in the xy plane, first order (F / |grad F|):
// accurate near the boundary, right sign everywhere.
double EllipseDistance(double x, double y, double a, double b) {
  const double F = (x / a) * (x / a) + (y / b) * (y / b) - 1.0;
  const double gx = 2.0 * x / (a * a), gy = 2.0 * y / (b * b);
  const double g = std::sqrt(gx * gx + gy * gy);
  return g > 1e-9 ? F / g : -std::min(a, b);
}

}  // namespace

double BodyHU(const Eigen::Vector3d& p, const TissueModel& t, double W) {
  const double dOut = EllipseDistance(p.x(), p.y(), t.bodySemiAxisXMm, t.bodySemiAxisYMm);
  if (dOut >= W) return t.airHU;
  const double dIn = EllipseDistance(p.x(), p.y(), t.bodySemiAxisXMm - t.bodyRimMm, t.bodySemiAxisYMm - t.bodyRimMm);
  return t.airHU + (t.softTissueHU - t.airHU) * PartialVolumeStep(-dOut, W) +
         (t.fatHU - t.softTissueHU) * PartialVolumeStep(-dIn, W);
}

double PartialVolumeHalfWidth(const PhantomOptions& options) {
  const double h = options.spacing.mean();
  const double b = options.tissue.blurSigmaVoxels * h;
  const double sigma = std::sqrt(h * h / 12.0 + b * b);
  return 1.88 * sigma;  // the cubic's slope at 0, 3/(4W), equals the Gaussian's, 1/(sqrt(2 pi) sigma)
}

double PartialVolumeStep(double d, double W) {
  if (d <= -W) return 0.0;
  if (d >= W) return 1.0;
  const double t = 0.5 * (d / W + 1.0);
  return t * t * (3.0 - 2.0 * t);
}

Volume<short> CTGrid(const PhantomOptions& options) {
  Volume<short> v;
  const Eigen::Vector3d& fov = options.tissue.fieldOfViewMm;
  for (int d = 0; d < 3; ++d) v.size[d] = static_cast<std::size_t>(std::max(1.0, std::round(fov[d] / options.spacing[d])));
  v.spacing = options.spacing;
  const Eigen::Vector3d n(static_cast<double>(v.size[0]), static_cast<double>(v.size[1]), static_cast<double>(v.size[2]));
  // Voxel centres symmetric about the field-of-view centre.
  v.origin = options.tissue.fieldOfViewCentre - 0.5 * (n - Eigen::Vector3d::Ones()).cwiseProduct(options.spacing);
  return v;
}

void SynthesizeCTOnGrid(const ScanGeometry& scan, const PhantomOptions& options, Volume<short>& grid,
                        ProgressSink& progress) {
  const TissueModel& t = options.tissue;
  const double W = PartialVolumeHalfWidth(options);
  const TubeLocator tube(scan, t.wallThicknessMm, W + 0.5);
  grid.Allocate(0);
  const std::uint64_t noiseKey = Hash(scan.anatomy.seed, scan.posture == Posture::Supine ? 11 : 12);
  const bool fluid = options.fluid;
  ForEachVoxel(grid, progress, [&](long i, long j, long k) {
    const Eigen::Vector3d p = grid.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
    const double outside = BodyHU(p, t, W);
    double hu = outside;
    const TubeSample q = tube.Query(p);
    if (q.near) {
      double content = t.airHU;
      if (fluid) {
        if (const FluidPool* pool = scan.PoolAt(q.u))
          content += (scan.fluidHU - t.airHU) * PartialVolumeStep(pool->level - scan.Height(p), W);
      }
      // A collapsed stretch: the walls touch, no air or fluid between them.
      if (!scan.collapsedU.empty()) content += (t.wallHU - content) * PartialVolumeStep(scan.CollapseDepth(q.u), W);
      const double a = PartialVolumeStep(q.innerDistance, W);
      const double b = std::min(a, PartialVolumeStep(q.outerDistance, W));
      hu = (1.0 - a) * content + (a - b) * t.wallHU + b * outside;
    }
    const std::size_t offset = grid.Offset(i, j, k);
    hu += t.noiseSigmaHU * HashToNormal(Hash(noiseKey, offset));
    grid.voxels[offset] = static_cast<short>(std::lround(std::clamp(hu, -1024.0, 3071.0)));
  });
}

Volume<short> SynthesizeCT(const ScanGeometry& scan, const PhantomOptions& options, ProgressSink& progress) {
  Volume<short> v = CTGrid(options);
  SynthesizeCTOnGrid(scan, options, v, progress);
  return v;
}

Volume<unsigned char> LumenLabel(const ScanGeometry& scan, const PhantomOptions& options, ProgressSink& progress) {
  const Volume<short> geometry = CTGrid(options);
  Volume<unsigned char> label = geometry.Like<unsigned char>(0);
  const TubeLocator tube(scan, options.tissue.wallThicknessMm, 1.0);
  ForEachVoxel(geometry, progress, [&](long i, long j, long k) {
    const Eigen::Vector3d p = geometry.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
    if (tube.IsLumen(p)) label.At(i, j, k) = 1;
  });
  return label;
}

}  // namespace phantom
}  // namespace colonmap
