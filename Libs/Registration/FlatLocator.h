#pragma once
// Point location in a flat (2D) triangle mesh, periodic in u (DESIGN §2.4): the flat image of a
// periodic-cut flattening is one period of a strip (u and u + period are the same wall point,
// Flattening/ConformalFlattening.h), so a query is tried at u + k period. Queries outside every
// triangle (beyond the ends of the rectangle, or in a rounding gap at the cut) get the nearest
// triangle and the barycentric coordinates of the nearest point on it (clamped). A uniform grid of
// triangle bounding boxes makes each query O(1) on average. Eigen in and out.
#include <Eigen/Core>

#include <optional>
#include <string>
#include <vector>

namespace colonmap::registration {

struct FlatHit {
  int face = -1;                       // triangle index in F
  Eigen::Vector3d bary{1.0, 0.0, 0.0};  // barycentric coordinates (>= 0, sum 1) in that face
  bool inside = false;                 // the query (or a periodic copy) lies in the face
  double distance = 0.0;               // flat distance to the face (0 when inside)
  double shift = 0.0;                  // k * period added to the query's u to reach the face
};

class FlatTriangleLocator {
 public:
  // uv: n x 2 flat vertex positions, F: m x 3 faces (m >= 1). period > 0: u is periodic with
  // that period; 0: no periodicity. Throws colonmap::Error for an empty mesh.
  FlatTriangleLocator(const Eigen::MatrixXd& uv, const Eigen::MatrixXi& F, double period);
  // The face containing p (the one with the largest smallest barycentric coordinate when p lies
  // on a shared edge: deterministic), else the nearest face.
  FlatHit Locate(const Eigen::Vector2d& p) const;

 private:
  bool Inside(const Eigen::Vector2d& q, FlatHit& best, double& bestMin) const;
  void Nearest(const Eigen::Vector2d& q, FlatHit& best) const;
  Eigen::Vector3d Barycentric(int f, const Eigen::Vector2d& q) const;
  long CellIndex(int i, int j) const { return static_cast<long>(j) * nx_ + i; }
  int CellX(double u) const;
  int CellY(double v) const;

  Eigen::MatrixXd uv_;
  Eigen::MatrixXi F_;
  double period_ = 0.0;
  Eigen::Vector2d lo_, hi_;
  double cell_ = 1.0;
  int nx_ = 1, ny_ = 1;
  std::vector<long> start_;  // CSR: faces of cell c are faces_[start_[c] .. start_[c+1])
  std::vector<int> faces_;
};

// The period of a periodic-cut flat map: the cut's two copies of each wall point (equal 3D
// positions, rows of `positions`) lie one period apart in u. Returns the median u difference
// over such pairs, or 0 when the mesh has no duplicated positions.
double FlatPeriodFromCut(const Eigen::MatrixXd& uv, const Eigen::MatrixXd& positions);

// A segment's flat width: `reported` (a flattening report's flatWidth) when given, else the cut's
// period; 0 when neither is known. A reported width the map contradicts is refused (InputError
// naming `what` and `path`, the report): off by more than 1% from the cut's period, or, without
// cut copies, more than twice or under half the span of u. A wrong width sizes pictures and
// wraps the map by the wrong period without a word.
double CheckedFlatPeriod(std::optional<double> reported, const Eigen::MatrixXd& uv, const Eigen::MatrixXd& positions,
                         const std::string& segment, const std::string& what, const std::string& path);

}  // namespace colonmap::registration
