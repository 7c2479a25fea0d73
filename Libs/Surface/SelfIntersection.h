#pragma once
// Whether a triangle surface passes through itself: pairs of faces whose triangles cross, found
// with a uniform grid of face bounding boxes (each pair tested once). Faces without a common
// vertex cross when an edge of one pierces the other; faces with one common vertex when the
// edge of one opposite it pierces the other; faces with a common edge only overlap when
// coplanar, which is not tested. A closed, consistently oriented surface without crossing
// pairs is embedded, so all its faces face the same side (a face cannot flip on its own).
// Double-precision orientation tests; coplanar touching is not counted. Eigen in and out,
// libigl style.
#include <Eigen/Core>
#include <array>
#include <vector>

namespace colonmap::surface {

struct SelfIntersections {
  long pairs = 0;                              // intersecting face pairs
  std::vector<std::array<int, 2>> examples;    // the first few (face indices), for messages
  std::vector<int> faces;                      // every face of a crossing pair (each once, increasing)
};

SelfIntersections FindSelfIntersections(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, std::size_t maxExamples = 8);

// The faces of the crossing pairs (each once, increasing).
std::vector<int> SelfIntersectingFaces(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F);

// Whether segment pq crosses triangle abc (strictly: not at an end point or along an edge).
bool SegmentCrossesTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d& a,
                            const Eigen::Vector3d& b, const Eigen::Vector3d& c);

}  // namespace colonmap::surface
