#pragma once
// A smooth space curve parametrised by arc length u (mm), with a rotation-minimising frame.
// Built from a control polygon whose corners are rounded by circular arcs of given radii (the
// bend radius, which must exceed the tube radius so that the tube has no local self-overlap),
// then lightly Gaussian-smoothed so that the curvature is continuous. Stored as samples every ~1 mm; between samples it
// is a cubic Hermite curve, so positions, tangents and nearest points are smooth and exact for
// the curve the rest of the phantom uses.
#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace colonmap {
namespace phantom {

class CenterlineCurve {
 public:
  CenterlineCurve() = default;
  // waypoints: control polygon (>= 2 points, LPS mm); the curve starts at the first and ends at
  //            the last waypoint and passes near (not through) the inner ones.
  // filletRadii: wanted bend radius at each waypoint (inner ones used); shortened where the
  //            polygon edges are too short (an edge is shared by its two corners in
  //            proportion to the tangent lengths they want).
  // sigmaMm:   Gaussian smoothing length along the rounded polygon's arc length.
  // stepMm:    target sample spacing (the actual one divides the length evenly).
  // normalHint: direction the frame's N starts closest to at u = 0.
  CenterlineCurve(const std::vector<Eigen::Vector3d>& waypoints, const std::vector<double>& filletRadii,
                  double sigmaMm, double stepMm, const Eigen::Vector3d& normalHint);

  double Length() const { return step_ * static_cast<double>(points_.size() - 1); }
  double Step() const { return step_; }
  std::size_t NumberOfSamples() const { return points_.size(); }
  const Eigen::Vector3d& Sample(std::size_t i) const { return points_[i]; }

  // Position, first and second derivative at u (clamped to [0, Length()]); outputs may be null.
  void Evaluate(double u, Eigen::Vector3d* p, Eigen::Vector3d* d1, Eigen::Vector3d* d2) const;
  Eigen::Vector3d Point(double u) const;
  // Right-handed orthonormal frame at u: T tangent, N rotation-minimising normal, B = T x N.
  void Frame(double u, Eigen::Vector3d& T, Eigen::Vector3d& N, Eigen::Vector3d& B) const;
  double Curvature(double u) const;

  // Arc length of the point of the curve nearest to p (global search; for occasional queries).
  double Closest(const Eigen::Vector3d& p) const;
  // Newton refinement of a nearest point that is known to be near u0.
  double Refine(const Eigen::Vector3d& p, double u0) const;

 private:
  double step_ = 1.0;
  std::vector<Eigen::Vector3d> points_;   // samples at u = i * step_
  std::vector<Eigen::Vector3d> tangents_; // dP/du at the samples (Hermite tangents)
  std::vector<Eigen::Vector3d> normals_;  // rotation-minimising N at the samples
};

}  // namespace phantom
}  // namespace colonmap
