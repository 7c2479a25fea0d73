#pragma once
// The supine and prone skeletons (centerlines) of a registration and their point-to-point
// correspondence, built from registration.vtp alone (DESIGN §2.5, "flattened centerline"): each
// flattened segment is cut into rows (bands of constant flat v, i.e. loops around the colon); a
// row's supine skeleton point is the area-weighted mass centre of its supine vertices, its prone
// skeleton point the mass centre of their prone images (PronePosition). A row and its image are
// the same loop of tissue, so row k of one skeleton matches row k of the other. Each row also
// keeps the rotation that best carries its supine loop onto the prone one (Kabsch), so a point
// near (not on) the supine skeleton maps with its offset turned the way the loop turned.
// Rows are ordered from the anal end to the cecum: segments R, S, D, T, A (SegmentId 4..0),
// each with v increasing (v runs from the anal end, README "ColonFlattening"). Eigen only.
#include "Core/TriangleMesh.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::views {

struct SkeletonOptions {
  double rowsPerWidth = 24;  // rows per flat width (one loop around): ~5 mm at 120 mm around
  int sectors = 8;           // a row counts only when its vertices cover all `sectors` around...
  int minSectors = 7;        // ...or at least this many of them (a loop, not a patch)
};

struct SkeletonRow {
  int segment = 0;     // SegmentId (0 when the mesh has no SegmentId)
  double v = 0;        // mean flat v of the row
  double weight = 0;   // supine area of the row (mm^2)
  Eigen::Vector3d supine{0, 0, 0}, prone{0, 0, 0};
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // supine loop -> prone loop
};

// Where a point sits along the supine skeleton: between rows `row` and `row + 1` at fraction t.
struct SkeletonLocation {
  int row = 0;
  double t = 0;
  double arc = 0;       // supine arc length from the first row (mm)
  double distance = 0;  // from the query to the skeleton (mm), for Project
  Eigen::Vector3d supine{0, 0, 0};
};

class LinkedSkeleton {
 public:
  // registration: the supine mesh with point arrays SupineFlatUV (2 components) and PronePosition
  // (3); SegmentId optional. Throws colonmap::Error (naming `what`) for missing arrays or fewer
  // than two usable rows.
  LinkedSkeleton(const TriangleMesh& registration, const std::string& what, const SkeletonOptions& options = {});

  const std::vector<SkeletonRow>& Rows() const { return rows_; }
  double Length() const { return arc_.back(); }

  // Nearest point of the supine skeleton polyline to p.
  SkeletonLocation Project(const Eigen::Vector3d& p) const;
  // The supine skeleton point at arc length `arc` (clamped to [0, Length()]).
  SkeletonLocation AtArc(double arc) const;

  Eigen::Vector3d Supine(const SkeletonLocation& l) const;
  Eigen::Vector3d Prone(const SkeletonLocation& l) const;
  Eigen::Matrix3d Rotation(const SkeletonLocation& l) const;  // slerp of the two rows' rotations
  // The prone point matching supine point o: c = Prone(l) + R(l) (o - Supine(l)), l = Project(o).
  // For o on the supine skeleton, c is the matching prone skeleton point (DESIGN §2.5).
  Eigen::Vector3d MapPoint(const Eigen::Vector3d& o) const;

 private:
  SkeletonLocation Locate(int row, double t) const;
  std::vector<SkeletonRow> rows_;
  std::vector<double> arc_;
};

}  // namespace colonmap::views
