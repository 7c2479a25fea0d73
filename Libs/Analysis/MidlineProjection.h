#pragma once
// Nearest points on a midline polyline for many query points (wall samples), libigl style.
// A uniform grid buckets the midline's segments; each query visits rings of grid cells around
// its own cell until no unvisited segment can be nearer than the best found (exact nearest
// point, not an approximation). Also gives the angle of each query around the midline in a
// rotation-minimising frame (double-reflection transport, Wang et al. 2008), so wall samples
// can be split into angular sectors.
//
//   MidlineProjection p = ProjectToMidline(wallPoints, midline);   // n x 3, m x 3, same units
//   p.arc(i), p.distance(i), p.angle(i)    // NaN arc for points past the ends or too far
//
// Eigen and std only.
#include <Eigen/Core>
#include <limits>

namespace colonmap {
namespace analysis {

// Cumulative arc length of a polyline (m x 3): m values, first 0, last the length.
Eigen::VectorXd ArcLength(const Eigen::MatrixXd& polyline);

// The point at arc length s along a polyline (m >= 2 points; arc = ArcLength(polyline)),
// linear between its points, clamped to its ends.
Eigen::Vector3d PointAtArc(const Eigen::MatrixXd& polyline, const Eigen::VectorXd& arc, double s);

// Rotation-minimising frame per polyline segment (m - 1 rows each): unit tangent T, normal N
// (N of segment 0 is the unit vector perpendicular to T nearest to normalHint, or to an axis
// if the hint is (near) parallel), binormal B = T x N. Zero-length segments copy the previous
// frame.
void SegmentFrames(const Eigen::MatrixXd& polyline, Eigen::MatrixXd& T, Eigen::MatrixXd& N, Eigen::MatrixXd& B,
                   const Eigen::Vector3d& normalHint = Eigen::Vector3d(0, 1, 0));

struct MidlineProjection {
  // Per query point (n rows):
  Eigen::VectorXd arc;       // arc length of the nearest midline point; NaN if excluded
  Eigen::VectorXd distance;  // distance to it, also for excluded points (NaN only if the search,
                             // which stops beyond maxDistance, met no segment)
  Eigen::VectorXd angle;     // angle around the midline in [0, 2 pi): atan2(d . B, d . N) with
                             // d = query - nearest point and (N, B) of the nearest segment
  Eigen::VectorXi segment;   // index of the nearest segment (-1 if none)
};

struct ProjectionOptions {
  // A point whose nearest midline point is an end point of the polyline with the point lying
  // beyond that end (its projection onto the end segment's line falls outside the polyline)
  // belongs to no arc length of the midline (end caps, tissue past a cut): arc = NaN.
  bool excludeBeyondEnds = true;
  // Points farther than this from the midline get arc = NaN (and cost no search beyond it).
  double maxDistance = std::numeric_limits<double>::infinity();
  // Grid cell edge (same units as the points); <= 0: 8 x the median segment length, at least
  // 1/64 of the bounding box diagonal.
  double cellSize = 0.0;
  Eigen::Vector3d normalHint{0, 1, 0};  // start of the rotation-minimising frame (see SegmentFrames)
};

// points: n x 3 query points; midline: m x 3 polyline (m >= 2). Exact nearest point on the
// polyline per query. Runs in O(n * (segments near each query)); ~0.1 s for 100K points.
MidlineProjection ProjectToMidline(const Eigen::MatrixXd& points, const Eigen::MatrixXd& midline,
                                   const ProjectionOptions& options = {});

}  // namespace analysis
}  // namespace colonmap
