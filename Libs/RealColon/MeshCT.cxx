#include "RealColon/MeshCT.h"

#include "Core/Error.h"
#include "Phantom/Random.h"
#include "Phantom/SynthesizeCT.h"
#include "Phantom/VoxelLoop.h"
#include "Surface/InsideMask.h"



#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <deque>
#include <limits>

namespace colonmap::realcolon {
namespace {

// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, 5.1.5).
Eigen::Vector3d ClosestOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                  const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// Unsigned distance to the mesh for voxels nearer than their limit (limitIn inside the mask,
// limitOut outside); farther voxels keep their limit. Triangles are bucketed by slab of slices
// and each slab is filled by one thread, so no two threads write one voxel.
std::vector<float> BandDistance(const TriangleMesh& mesh, const Volume<short>& grid, const Volume<unsigned char>& mask,
                                double limitIn, double limitOut, ProgressSink& progress, double from, double to) {
  const long nx = static_cast<long>(grid.size[0]), ny = static_cast<long>(grid.size[1]), nz = static_cast<long>(grid.size[2]);
  std::vector<float> dist(grid.NumberOfVoxels());
  for (std::size_t v = 0; v < dist.size(); ++v) dist[v] = static_cast<float>(mask.voxels[v] ? limitIn : limitOut);
  const Eigen::Vector3d h = grid.spacing;
  const long slab = 4;
  const long slabs = (nz + slab - 1) / slab;
  std::vector<std::vector<int>> bySlab(static_cast<std::size_t>(slabs));
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const double zlo = std::min({mesh.V(mesh.F(f, 0), 2), mesh.V(mesh.F(f, 1), 2), mesh.V(mesh.F(f, 2), 2)}) - limitOut;
    const double zhi = std::max({mesh.V(mesh.F(f, 0), 2), mesh.V(mesh.F(f, 1), 2), mesh.V(mesh.F(f, 2), 2)}) + limitOut;
    const long k0 = std::max(0L, static_cast<long>(std::ceil((zlo - grid.origin.z()) / h.z())));
    const long k1 = std::min(nz - 1, static_cast<long>(std::floor((zhi - grid.origin.z()) / h.z())));
    for (long s = k0 / slab; s <= k1 / slab && k0 <= k1; ++s) bySlab[static_cast<std::size_t>(s)].push_back(static_cast<int>(f));
  }
  const long group = 16;  // slabs per progress report
  for (long s0 = 0; s0 < slabs; s0 += group) {
    const long s1 = std::min(slabs, s0 + group);
#pragma omp parallel for schedule(dynamic, 1)
    for (long s = s0; s < s1; ++s) {
      const long kLo = s * slab, kHi = std::min(nz - 1, kLo + slab - 1);
      for (int f : bySlab[static_cast<std::size_t>(s)]) {
        const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
        Eigen::Vector3d n = (b - a).cross(c - a);
        const double len = n.norm();
        if (len > 0) n /= len;
        const Eigen::Vector3d lo = a.cwiseMin(b).cwiseMin(c).array() - limitOut, hi = a.cwiseMax(b).cwiseMax(c).array() + limitOut;
        const Eigen::Vector3d ilo = (lo - grid.origin).cwiseQuotient(h), ihi = (hi - grid.origin).cwiseQuotient(h);
        const long i0 = std::max(0L, static_cast<long>(std::ceil(ilo.x()))), i1 = std::min(nx - 1, static_cast<long>(std::floor(ihi.x())));
        const long j0 = std::max(0L, static_cast<long>(std::ceil(ilo.y()))), j1 = std::min(ny - 1, static_cast<long>(std::floor(ihi.y())));
        const long k0 = std::max(kLo, static_cast<long>(std::ceil(ilo.z()))), k1 = std::min(kHi, static_cast<long>(std::floor(ihi.z())));
        for (long k = k0; k <= k1; ++k)
          for (long j = j0; j <= j1; ++j)
            for (long i = i0; i <= i1; ++i) {
              const std::size_t v = static_cast<std::size_t>(i + nx * (j + ny * k));
              const Eigen::Vector3d p = grid.origin + Eigen::Vector3d(i * h.x(), j * h.y(), k * h.z());
              const double best = dist[v];
              if (len > 0 && std::fabs(n.dot(p - a)) >= best) continue;  // the plane is a lower bound
              const double d = (p - ClosestOnTriangle(p, a, b, c)).norm();
              if (d < best) dist[v] = static_cast<float>(d);
            }
      }
    }
    progress.Report(from + (to - from) * static_cast<double>(s1) / static_cast<double>(slabs));
  }
  return dist;
}

}  // namespace

Volume<unsigned char> MeshLumenMask(const TriangleMesh& lumen, const Volume<short>& grid) {
  Volume<unsigned char> mask = grid.Like<unsigned char>(0);
  surface::FillInsideMask(lumen, mask);
  return mask;
}

Volume<unsigned char> FluidPools(const MeshScan& scan, const Volume<unsigned char>& mask, double W) {
  Volume<unsigned char> pool = mask.Like<unsigned char>(0);
  const long nx = static_cast<long>(mask.size[0]), ny = static_cast<long>(mask.size[1]), nz = static_cast<long>(mask.size[2]);
  const auto height = [&](long i, long j, long k) {
    return -scan.down.dot(mask.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k))));
  };
  const long step[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (std::size_t q = 0; q < scan.pools.size() && q < 254; ++q) {
    const FluidPoolSpec& spec = scan.pools[q];
    const unsigned char id = static_cast<unsigned char>(q + 1);
    // The seed voxel, or the first lumen voxel above it.
    Eigen::Vector3d idx = mask.PhysicalToIndex(spec.seed);
    long si = std::lround(idx.x()), sj = std::lround(idx.y()), sk = std::lround(idx.z());
    bool found = false;
    const Eigen::Vector3d up = -mask.direction.transpose() * scan.down;
    for (int t = 0; t <= 8 && !found; ++t) {
      const long i = std::lround(idx.x() + t * up.x()), j = std::lround(idx.y() + t * up.y()), k = std::lround(idx.z() + t * up.z());
      if (i < 0 || j < 0 || k < 0 || i >= nx || j >= ny || k >= nz) break;
      if (mask.At(i, j, k)) si = i, sj = j, sk = k, found = true;
    }
    if (!found || pool.At(si, sj, sk)) continue;
    std::deque<std::array<long, 3>> queue{{si, sj, sk}};
    pool.At(si, sj, sk) = id;
    while (!queue.empty()) {
      const auto [i, j, k] = queue.front();
      queue.pop_front();
      for (const auto& s : step) {
        const long a = i + s[0], b = j + s[1], c = k + s[2];
        if (a < 0 || b < 0 || c < 0 || a >= nx || b >= ny || c >= nz) continue;
        if (!mask.At(a, b, c) || pool.At(a, b, c) || height(a, b, c) >= spec.level + W) continue;
        pool.At(a, b, c) = id;
        queue.push_back({a, b, c});
      }
    }
  }
  // The wall voxels next to a pool hold its fluid in their lumen part.
  Volume<unsigned char> grown = pool;
  for (long k = 1; k + 1 < nz; ++k)
    for (long j = 1; j + 1 < ny; ++j)
      for (long i = 1; i + 1 < nx; ++i) {
        if (mask.At(i, j, k) || pool.At(i, j, k)) continue;
        for (const auto& s : step) {
          const unsigned char id = pool.At(i + s[0], j + s[1], k + s[2]);
          if (id && height(i, j, k) < scan.pools[id - 1].level + W) {
            grown.At(i, j, k) = id;
            break;
          }
        }
      }
  return grown;
}

// How far (mm of material s) each voxel lies inside a collapsed stretch (positive inside; -inf
// where no voxel needs it), for the lumen and the band outside it: each voxel takes the s of the
// axis point it is reached from first by a breadth-first flood through the lumen (face
// neighbours), started at the voxels of the axis points, and the band voxels that of the lumen
// voxel nearest in the same way. Through the lumen, not across the wall: a voxel next to a
// touching loop takes its own loop's s.
std::vector<float> CollapseDepth(const MeshScan& scan, const Volume<short>& grid, const Volume<unsigned char>& mask,
                                 const std::vector<float>& dist, double limitOut) {
  const std::size_t n = grid.NumberOfVoxels();
  if (scan.axis.rows() != scan.axisS.size() || scan.axis.rows() < 2)
    throw Error("mesh CT: the axis and its material s differ in length");
  std::vector<float> s(n, std::numeric_limits<float>::quiet_NaN());
  std::deque<std::size_t> queue;
  for (Eigen::Index a = 0; a < scan.axis.rows(); ++a) {
    const Eigen::Vector3d idx = grid.PhysicalToIndex(scan.axis.row(a).transpose());
    const long i = std::lround(idx.x()), j = std::lround(idx.y()), k = std::lround(idx.z());
    if (i < 0 || j < 0 || k < 0 || i >= long(grid.size[0]) || j >= long(grid.size[1]) || k >= long(grid.size[2])) continue;
    const std::size_t v = grid.Offset(std::size_t(i), std::size_t(j), std::size_t(k));
    if (!mask.voxels[v] || !std::isnan(s[v])) continue;
    s[v] = static_cast<float>(scan.axisS(a));
    queue.push_back(v);
  }
  const long sx = 1, sy = long(grid.size[0]), sz = long(grid.size[0] * grid.size[1]);
  // Two floods: through the lumen first, then from it into the band outside. The band is shared
  // by loops that touch: a flood through it would hand a voxel by the wall the other loop's s.
  const auto flood = [&](const auto& allowed) {
    while (!queue.empty()) {
      const std::size_t v = queue.front();
      queue.pop_front();
      const std::size_t i = v % grid.size[0], j = (v / grid.size[0]) % grid.size[1], k = v / (grid.size[0] * grid.size[1]);
      const bool ok[6] = {i > 0, i + 1 < grid.size[0], j > 0, j + 1 < grid.size[1], k > 0, k + 1 < grid.size[2]};
      const long step[6] = {-sx, sx, -sy, sy, -sz, sz};
      for (int d = 0; d < 6; ++d) {
        if (!ok[d]) continue;
        const std::size_t w = static_cast<std::size_t>(long(v) + step[d]);
        if (!std::isnan(s[w]) || !allowed(w)) continue;
        s[w] = s[v];
        queue.push_back(w);
      }
    }
  };
  flood([&](std::size_t w) { return mask.voxels[w] != 0; });
  for (std::size_t v = 0; v < n; ++v)
    if (mask.voxels[v] && !std::isnan(s[v])) queue.push_back(v);
  flood([&](std::size_t w) { return !mask.voxels[w] && dist[w] < limitOut; });
  std::vector<float> depth(n, -std::numeric_limits<float>::infinity());
  for (std::size_t v = 0; v < n; ++v) {
    if (std::isnan(s[v])) continue;
    for (const auto& [s0, s1] : scan.collapsedS)
      depth[v] = std::max(depth[v], static_cast<float>(std::min(s[v] - s0, s1 - s[v])));
  }
  return depth;
}

void SynthesizeMeshCT(const MeshScan& scan, const phantom::PhantomOptions& options, Volume<short>& grid,
                      ProgressSink& progress) {
  if (!scan.lumen || scan.lumen->F.rows() == 0) throw Error("mesh CT: no lumen surface");
  const phantom::TissueModel& t = options.tissue;
  const double W = phantom::PartialVolumeHalfWidth(options);
  const double half = 0.5 * grid.spacing.maxCoeff();
  const double limitIn = W + half, limitOut = t.wallThicknessMm + W + half;
  progress.Report(0.0);
  const Volume<unsigned char> mask = MeshLumenMask(*scan.lumen, grid);
  progress.Report(0.15);
  const std::vector<float> dist = BandDistance(*scan.lumen, grid, mask, limitIn, limitOut, progress, 0.15, 0.7);
  const Volume<unsigned char> pools = options.fluid && !scan.pools.empty() ? FluidPools(scan, mask, W) : mask.Like<unsigned char>(0);
  const std::vector<float> collapse =
      scan.collapsedS.empty() ? std::vector<float>() : CollapseDepth(scan, grid, mask, dist, limitOut);
  progress.Report(0.75);
  grid.Allocate(0);
  SubProgress rest(progress, 0.75, 1.0);
  phantom::ForEachVoxel(grid, rest, [&](long i, long j, long k) {
    const std::size_t v = grid.Offset(static_cast<std::size_t>(i), static_cast<std::size_t>(j), static_cast<std::size_t>(k));
    const Eigen::Vector3d p = grid.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
    const double outside = phantom::BodyHU(p, t, W);
    const double u = dist[v];
    double hu = outside;
    if (mask.voxels[v] || u < limitOut) {
      const double d = mask.voxels[v] ? -u : u;
      double content = t.airHU;
      if (const unsigned char id = pools.voxels[v])
        content += (scan.fluidHU - t.airHU) * phantom::PartialVolumeStep(scan.pools[id - 1].level + scan.down.dot(p), W);
      // A collapsed stretch: the walls touch, no air or fluid between them.
      if (!collapse.empty()) content += (t.wallHU - content) * phantom::PartialVolumeStep(collapse[v], W);
      const double a = phantom::PartialVolumeStep(d, W);
      const double b = std::min(a, phantom::PartialVolumeStep(d - t.wallThicknessMm, W));
      hu = (1.0 - a) * content + (a - b) * t.wallHU + b * outside;
    }
    hu += t.noiseSigmaHU * phantom::HashToNormal(phantom::Hash(scan.noiseKey, v));
    grid.voxels[v] = static_cast<short>(std::lround(std::clamp(hu, -1024.0, 3071.0)));
  });
}

}  // namespace colonmap::realcolon
