#pragma once
// Dilatation K = sigma_max / sigma_min = (1 + |mu|) / (1 - |mu|) of the piecewise affine map
// between two triangle meshes with the same connectivity (face k of `from` onto face k of `to`,
// each triangle in its own plane), and its per-segment statistics.
#include <Core/TriangleMesh.h>

#include <Eigen/Core>
#include <array>
#include <cstddef>

namespace colonmap {
namespace phantom {

// Per-face K (>= 1; +inf for a degenerate face). Throws std::invalid_argument if the face
// arrays differ.
Eigen::VectorXd FaceDilatation(const TriangleMesh& from, const TriangleMesh& to);

// Segment of each face: the SegmentId point value of its first vertex (-1 without the array).
Eigen::VectorXi FaceSegments(const TriangleMesh& mesh);

struct DilatationSummary {
  double mean = 0.0, median = 0.0, p90 = 0.0, max = 0.0;  // over faces, unweighted
  std::size_t count = 0;
};
struct DilatationStats {
  std::array<DilatationSummary, 5> segment;  // A, T, D, S, R
  DilatationSummary all;
};

// Statistics of K per segment (faceSegment values 0..4; others count only in `all`).
DilatationStats SummarizeDilatation(const Eigen::VectorXd& K, const Eigen::VectorXi& faceSegment);

}  // namespace phantom
}  // namespace colonmap
