#include "TrueWall.h"

#include <algorithm>
#include <cmath>

namespace colonmap {
namespace phantom {

TriangleMesh TrueWall(const ScanGeometry& scan, const PhantomOptions& options) {
  const double L = scan.anatomy.length;
  const int ns = std::max(2, static_cast<int>(std::lround(L / std::max(options.meshStepMm, 0.05))) + 1);
  const int nt = std::max(3, options.meshPointsAround);
  const double twoPi = 2.0 * 3.14159265358979323846;
  TriangleMesh mesh;
  mesh.V.resize(static_cast<Eigen::Index>(ns) * nt, 3);
  Eigen::MatrixXd S(mesh.V.rows(), 1), Th(mesh.V.rows(), 1), Seg(mesh.V.rows(), 1);
#pragma omp parallel for schedule(static)
  for (int i = 0; i < ns; ++i) {
    const double s = i + 1 == ns ? L : L * i / (ns - 1);
    const int seg = scan.anatomy.SegmentOf(s);
    for (int j = 0; j < nt; ++j) {
      const double theta = twoPi * j / nt;
      const Eigen::Index v = static_cast<Eigen::Index>(i) * nt + j;
      mesh.V.row(v) = scan.WallPoint(s, theta).transpose();
      S(v, 0) = s;
      Th(v, 0) = theta;
      Seg(v, 0) = seg;
    }
  }
  // Quad (i, j), (i+1, j), (i+1, j+1), (i, j+1): d/ds x d/dtheta points inwards, so (s, theta)
  // counter-clockwise seen from inside the lumen.
  mesh.F.resize(2 * static_cast<Eigen::Index>(ns - 1) * nt, 3);
  Eigen::Index f = 0;
  for (int i = 0; i + 1 < ns; ++i)
    for (int j = 0; j < nt; ++j) {
      const int a = i * nt + j, b = (i + 1) * nt + j, c = (i + 1) * nt + (j + 1) % nt, d = i * nt + (j + 1) % nt;
      mesh.F.row(f++) << a, b, c;
      mesh.F.row(f++) << a, c, d;
    }
  mesh.pointData["MaterialS"] = DataArray{S, false};
  mesh.pointData["MaterialTheta"] = DataArray{Th, false};
  mesh.pointData["SegmentId"] = DataArray{Seg, true};
  return mesh;
}

}  // namespace phantom
}  // namespace colonmap
