#pragma once
// Point queries against one scan's colon tube: material coordinates (s, theta) of the nearest
// centreline point's cross-section and signed distances to the lumen surface and the outer wall
// surface. A uniform grid of cells lists the coarse centreline pieces whose tube band reaches
// the cell, so a query only looks at the few nearby pieces; Newton then finds the exact foot on
// the smooth centreline. Read-only after construction: safe to query from many threads.
#include "ScanGeometry.h"

#include <Eigen/Core>
#include <vector>

namespace colonmap {
namespace phantom {

struct TubeSample {
  bool near = false;    // p is inside the band (outer wall + bandMm); other fields valid only then
  int end = 0;          // -1 past the cecum end (hemispheric cap), +1 past the anal end, else 0
  double u = 0.0;       // arc length of the foot on the scan's centreline
  double s = 0.0;       // material s of the foot
  double theta = 0.0;   // material theta in [0, 2 pi)
  double rho = 0.0;     // distance from the foot (from the end point in a cap)
  bool deepLumen = false;     // rho is far inside the lumen: radii below are bounds only
  double innerRadius = 0.0;   // lumen surface radius r(s, theta)
  double outerRadius = 0.0;   // outer wall surface radius
  // Signed distances (mm, positive away from the lumen), first-order: (rho - r) divided by the
  // slope factor of the radial height field; exact zero set = the true surface.
  double innerDistance = 0.0;
  double outerDistance = 0.0;
};

class TubeLocator {
 public:
  // wallThicknessMm: outer wall = base radius + this; bandMm: extra reach beyond the outer wall.
  TubeLocator(const ScanGeometry& scan, double wallThicknessMm, double bandMm, double cellMm = 6.0);

  TubeSample Query(const Eigen::Vector3d& p) const;
  // Inside the lumen (air or fluid) of the closed tube (with end caps), outside collapsed stretches.
  bool IsLumen(const Eigen::Vector3d& p) const;

  const ScanGeometry& Scan() const { return *scan_; }

 private:
  const ScanGeometry* scan_;
  double wall_, band_, cell_;
  int stride_ = 4;                       // centreline samples per coarse piece
  std::vector<Eigen::Vector3d> nodes_;   // coarse polyline
  std::vector<double> nodeU_;
  std::vector<double> reach_;            // per coarse piece
  std::vector<double> innerBound_;       // per centreline sample: lower bound of r over theta
  Eigen::Vector3d gridOrigin_;
  int dims_[3] = {0, 0, 0};
  std::vector<int> cellStart_;           // CSR: pieces of cell c are pieceIndex_[cellStart_[c] .. cellStart_[c+1])
  std::vector<int> pieceIndex_;
};

}  // namespace phantom
}  // namespace colonmap
