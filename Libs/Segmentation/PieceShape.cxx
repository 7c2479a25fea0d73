#include "Segmentation/PieceShape.h"

#include "Analysis/ShortestPaths.h"
#include "Core/Error.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace colonmap::segmentation {
namespace {

// The mask's blocks: position (mean voxel), voxel count, and their 26-neighbour graph.
struct Blocks {
  std::vector<Eigen::Vector3d> position;
  std::vector<double> voxels;
  analysis::EdgeGraph graph;
};

// Each cell of about blockMm is split into its own 26-connected pieces of mask (a cell that
// straddles the thin wall between two touching loops gives one block per loop), and two blocks
// are joined when a voxel of one touches a voxel of the other: the block graph never crosses a
// wall that the voxels do not cross.
Blocks MakeBlocks(const Volume<unsigned char>& mask, double blockMm) {
  std::array<std::size_t, 3> b{};
  for (int d = 0; d < 3; ++d)
    b[d] = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(blockMm / mask.spacing[d])));
  const std::size_t nx = mask.size[0], ny = mask.size[1], nz = mask.size[2];
  // Cell index along each axis, looked up (the flood below asks for it 26 times per voxel).
  std::array<std::vector<std::size_t>, 3> cellAlong;
  for (int d = 0; d < 3; ++d)
    for (std::size_t i = 0; i < mask.size[d]; ++i) cellAlong[d].push_back(i / b[d]);
  const auto cellOf = [&](std::size_t i, std::size_t j, std::size_t k) {
    return std::array<std::size_t, 3>{cellAlong[0][i], cellAlong[1][j], cellAlong[2][k]};
  };
  std::vector<int> block(mask.voxels.size(), -1);
  Blocks blocks;
  std::vector<Eigen::Vector3d> indexSum;
  std::vector<std::size_t> stack;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const std::size_t v0 = mask.Offset(i, j, k);
        if (!mask.voxels[v0] || block[v0] >= 0) continue;
        // A new block: the mask voxels of this cell 26-connected to v0 within the cell.
        const int id = static_cast<int>(blocks.voxels.size());
        const auto cell = cellOf(i, j, k);
        blocks.voxels.push_back(0.0);
        indexSum.push_back(Eigen::Vector3d::Zero());
        block[v0] = id;
        stack.assign(1, v0);
        while (!stack.empty()) {
          const std::size_t v = stack.back();
          stack.pop_back();
          const std::size_t x = v % nx, y = (v / nx) % ny, z = v / (nx * ny);
          blocks.voxels.back() += 1.0;
          indexSum.back() += Eigen::Vector3d(double(x), double(y), double(z));
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                const long X = long(x) + dx, Y = long(y) + dy, Z = long(z) + dz;
                if (X < 0 || Y < 0 || Z < 0 || X >= long(nx) || Y >= long(ny) || Z >= long(nz)) continue;
                if (cellOf(std::size_t(X), std::size_t(Y), std::size_t(Z)) != cell) continue;
                const std::size_t w = mask.Offset(std::size_t(X), std::size_t(Y), std::size_t(Z));
                if (!mask.voxels[w] || block[w] >= 0) continue;
                block[w] = id;
                stack.push_back(w);
              }
        }
      }
  if (blocks.voxels.empty()) throw Error("piece shape: the piece has no voxels");
  for (std::size_t v = 0; v < indexSum.size(); ++v)
    blocks.position.push_back(mask.IndexToPhysical(indexSum[v] / blocks.voxels[v]));
  blocks.graph.vertices = static_cast<int>(blocks.voxels.size());
  // Edges: blocks whose voxels touch (the 13 forward neighbours of every voxel), each pair once.
  std::vector<std::pair<int, int>> edges;
  for (std::size_t k = 0; k < nz; ++k)
    for (std::size_t j = 0; j < ny; ++j)
      for (std::size_t i = 0; i < nx; ++i) {
        const int a = block[mask.Offset(i, j, k)];
        if (a < 0) continue;
        for (int dz = 0; dz <= 1; ++dz)
          for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
              if (dz == 0 && (dy < 0 || (dy == 0 && dx <= 0))) continue;
              const long X = long(i) + dx, Y = long(j) + dy, Z = long(k) + dz;
              if (X < 0 || Y < 0 || X >= long(nx) || Y >= long(ny) || Z >= long(nz)) continue;
              const int c = block[mask.Offset(std::size_t(X), std::size_t(Y), std::size_t(Z))];
              if (c >= 0 && c != a) edges.emplace_back(std::min(a, c), std::max(a, c));
            }
      }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  for (const auto& [a, c] : edges) {
    blocks.graph.edges.emplace_back(a, c);
    blocks.graph.lengths.push_back((blocks.position[std::size_t(a)] - blocks.position[std::size_t(c)]).norm());
  }
  return blocks;
}

int Farthest(const std::vector<double>& distance) {
  int best = 0;
  for (std::size_t v = 0; v < distance.size(); ++v)
    if (std::isfinite(distance[v]) && distance[v] > distance[static_cast<std::size_t>(best)]) best = static_cast<int>(v);
  return best;
}

// Voxel-weighted centroid of the blocks whose distance lies in [lo, hi].
Eigen::Vector3d BandCentroid(const Blocks& blocks, const std::vector<double>& distance, double lo, double hi) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double weight = 0.0;
  for (std::size_t v = 0; v < distance.size(); ++v)
    if (distance[v] >= lo && distance[v] <= hi) {
      sum += blocks.voxels[v] * blocks.position[v];
      weight += blocks.voxels[v];
    }
  return weight > 0.0 ? Eigen::Vector3d(sum / weight) : blocks.position[static_cast<std::size_t>(Farthest(distance))];
}

// The end at the extremity far from `other`: distances from the other extremity are close to
// planar cross-sections there (distances from the end's own extremity, which sits on the rim
// of the cap, would pull the centroid towards that rim).
PieceEnd EndFrom(const Blocks& blocks, const std::vector<double>& fromOther, double length) {
  PieceEnd end;
  end.point = BandCentroid(blocks, fromOther, length - std::min(15.0, 0.3 * length), length - std::min(5.0, 0.1 * length));
  const Eigen::Vector3d inner =
      BandCentroid(blocks, fromOther, length - std::min(40.0, 0.6 * length), length - std::min(25.0, 0.45 * length));
  const Eigen::Vector3d d = end.point - inner;
  end.outward = d.norm() > 1e-9 ? Eigen::Vector3d(d.normalized()) : Eigen::Vector3d::Zero();
  return end;
}

}  // namespace

PieceShape MeasurePieceShape(const Volume<unsigned char>& mask, double blockMm) {
  const Blocks blocks = MakeBlocks(mask, blockMm);
  const analysis::ShortestPathGraph graph(blocks.graph);
  const int a = Farthest(graph.From(0));
  const std::vector<double> fromA = graph.From(a);
  const int b = Farthest(fromA);
  const std::vector<double> fromB = graph.From(b);
  PieceShape shape;
  shape.lengthMm = fromA[static_cast<std::size_t>(b)];
  shape.ends[0] = EndFrom(blocks, fromB, shape.lengthMm);  // at extremity a
  shape.ends[1] = EndFrom(blocks, fromA, shape.lengthMm);  // at extremity b
  return shape;
}

}  // namespace colonmap::segmentation
