#pragma once
// A 3D image on a regular grid in LPS millimetres, free of ITK so that the math layer and its
// tests compile fast. Conversion to and from itk::Image lives only in Libs/IO.
#include "Core/Cancel.h"

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <vector>

namespace colonmap {

template <typename T>
struct Volume {
  std::array<std::size_t, 3> size{{0, 0, 0}};   // voxels along i, j, k
  Eigen::Vector3d spacing{1.0, 1.0, 1.0};       // mm
  Eigen::Vector3d origin{0.0, 0.0, 0.0};        // LPS mm of voxel (0,0,0) centre
  Eigen::Matrix3d direction = Eigen::Matrix3d::Identity();  // columns: i, j, k axes in LPS
  std::vector<T> voxels;                        // i fastest, then j, then k

  std::size_t NumberOfVoxels() const { return size[0] * size[1] * size[2]; }
  void Allocate(const T& value = T()) { voxels.assign(NumberOfVoxels(), value); }
  std::size_t Offset(std::size_t i, std::size_t j, std::size_t k) const {
    return i + size[0] * (j + size[1] * k);
  }
  T& At(std::size_t i, std::size_t j, std::size_t k) { return voxels[Offset(i, j, k)]; }
  const T& At(std::size_t i, std::size_t j, std::size_t k) const { return voxels[Offset(i, j, k)]; }

  // The grid (size, spacing, origin, direction) with pixel type U and no voxels yet.
  template <typename U>
  Volume<U> EmptyLike() const {
    Volume<U> v;
    v.size = size;
    v.spacing = spacing;
    v.origin = origin;
    v.direction = direction;
    return v;
  }

  // An image of pixel type U on the same grid, every voxel set to `value`.
  template <typename U>
  Volume<U> Like(const U& value = U()) const {
    Volume<U> v = EmptyLike<U>();
    v.Allocate(value);
    return v;
  }

  // The same, filled piece by piece with `progress` polled between pieces (a CT-sized image
  // takes a good part of a second to allocate and touch).
  template <typename U>
  Volume<U> Like(const U& value, ProgressSink* progress) const {
    Volume<U> v = EmptyLike<U>();
    FillReporting(v.voxels, NumberOfVoxels(), value, progress);
    return v;
  }

  // A copy, made piece by piece with `progress` polled between pieces.
  Volume<T> Copy(ProgressSink* progress) const {
    Volume<T> v = EmptyLike<T>();
    AssignReporting(voxels.data(), voxels.size(), v.voxels, progress);
    return v;
  }

  // Continuous index -> LPS mm.
  Eigen::Vector3d IndexToPhysical(const Eigen::Vector3d& index) const {
    return origin + direction * spacing.cwiseProduct(index);
  }
  // LPS mm -> continuous index.
  Eigen::Vector3d PhysicalToIndex(const Eigen::Vector3d& p) const {
    return (direction.transpose() * (p - origin)).cwiseQuotient(spacing);
  }
};

// An image of pixel type T on the grid of `in`, each voxel map(in's voxel), made piece by piece
// with `progress` (when given) polled between pieces.
template <typename T, typename K, typename Map>
Volume<T> MapVoxels(const Volume<K>& in, Map map, ProgressSink* progress = nullptr) {
  Volume<T> out = in.template EmptyLike<T>();
  out.voxels.reserve(in.voxels.size());
  ForPieces(in.voxels.size(), kPollPiece, progress, [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) out.voxels.push_back(static_cast<T>(map(in.voxels[i])));
  });
  return out;
}

}  // namespace colonmap
