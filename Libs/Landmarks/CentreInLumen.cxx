#include "Landmarks/CentreInLumen.h"

#include "Core/Error.h"
#include "Landmarks/Centerline.h"
#include "Surface/VtkConversion.h"

#include <Eigen/Geometry>
#include <vtkCellLocator.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <algorithm>

namespace colonmap::landmarks {

namespace {

// The nearest wall point of p and the wall's inward unit normal there.
struct WallHit {
  Eigen::Vector3d point, inward;
  double signedDistance = 0;  // > 0 inside the lumen
};

class Wall {
 public:
  Wall(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F) : V_(V), F_(F) {
    TriangleMesh m;
    m.V = V;
    m.F = F;
    surface::ToPolyData(m, poly_);
    locator_->SetDataSet(poly_);
    locator_->BuildLocator();
    // Inside is where the face normals point when the signed volume is negative.
    double volume = 0;
    for (Eigen::Index f = 0; f < F.rows(); ++f)
      volume += Eigen::Vector3d(V.row(F(f, 0))).dot(Eigen::Vector3d(V.row(F(f, 1))).cross(Eigen::Vector3d(V.row(F(f, 2)))));
    inwardSign_ = volume < 0 ? 1.0 : -1.0;
  }

  WallHit Nearest(const Eigen::Vector3d& p) const {
    double x[3], d2 = 0;
    vtkIdType cell = -1;
    int sub = 0;
    locator_->FindClosestPoint(p.data(), x, cell_, cell, sub, d2);
    WallHit h;
    h.point = Eigen::Vector3d(x[0], x[1], x[2]);
    const Eigen::Vector3d a = V_.row(F_(cell, 0)), b = V_.row(F_(cell, 1)), c = V_.row(F_(cell, 2));
    h.inward = inwardSign_ * (b - a).cross(c - a).normalized();
    const Eigen::Vector3d d = p - h.point;
    h.signedDistance = d.dot(h.inward) >= 0 ? d.norm() : -d.norm();
    return h;
  }

 private:
  const Eigen::MatrixXd& V_;
  const Eigen::MatrixXi& F_;
  vtkNew<vtkPolyData> poly_;
  vtkNew<vtkCellLocator> locator_;
  vtkNew<vtkGenericCell> cell_;
  double inwardSign_ = 1.0;
};

void Clearance(const Wall& wall, const Eigen::MatrixXd& P, double& mean, long& outside) {
  mean = 0;
  outside = 0;
  for (Eigen::Index i = 0; i < P.rows(); ++i) {
    const double s = wall.Nearest(P.row(i).transpose()).signedDistance;
    mean += s;
    outside += s < 0;
  }
  mean /= static_cast<double>(std::max<Eigen::Index>(1, P.rows()));
}

}  // namespace

CentringResult CentreInLumen(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& curve,
                             const CentringOptions& o, ProgressSink& progress) {
  if (curve.rows() < 2 || F.rows() == 0) throw Error("centring needs a curve and a surface");
  Eigen::MatrixXd P = ResamplePolyline(curve, o.sampleMm);
  if (P.rows() < 3) throw Error("centring needs a curve longer than two samples");
  const Wall wall(V, F);
  CentringResult r;
  Clearance(wall, P, r.meanClearanceBefore, r.outsideBefore);
  for (int it = 0; it < o.iterations; ++it) {
    const double step = o.maxStepMm * (1.0 - 0.9 * it / std::max(1, o.iterations - 1));
    Eigen::MatrixXd Q = P;
    for (Eigen::Index i = 1; i + 1 < P.rows(); ++i) {
      const Eigen::Vector3d p = P.row(i);
      const Eigen::Vector3d t = (P.row(i + 1) - P.row(i - 1)).transpose().normalized();
      const WallHit h = wall.Nearest(p);
      // Up the signed distance: away from the nearest wall point inside, towards it (and
      // through) outside.
      const Eigen::Vector3d d = p - h.point;
      Eigen::Vector3d g = d.norm() > 1e-9 ? Eigen::Vector3d((h.signedDistance >= 0 ? 1.0 : -1.0) * d.normalized()) : h.inward;
      g -= g.dot(t) * t;  // within the normal plane: the curve does not slide along itself
      const Eigen::Vector3d mid = 0.5 * (P.row(i - 1) + P.row(i + 1)).transpose();
      Q.row(i) = (p + step * g + o.smoothing * (mid - p)).transpose();
    }
    P = (it % 5 == 4) ? ResamplePolyline(Q, o.sampleMm) : Q;
    progress.Report(static_cast<double>(it + 1) / o.iterations);
  }
  r.points = ResamplePolyline(P, o.sampleMm);
  Clearance(wall, r.points, r.meanClearanceAfter, r.outsideAfter);
  return r;
}

}  // namespace colonmap::landmarks
