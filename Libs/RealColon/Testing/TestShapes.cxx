#include "TestShapes.h"

#include "Surface/VtkConversion.h"

#include <vtkFlyingEdges3D.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPolyData.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

namespace colonmap::realcolon::testing {

TriangleMesh Cylinder(double r, double h, int n, int m) {
  TriangleMesh c;
  c.V.resize((m + 1) * n, 3);
  for (int i = 0; i <= m; ++i)
    for (int j = 0; j < n; ++j) {
      const double a = 2.0 * M_PI * j / n;
      c.V.row(i * n + j) << r * std::cos(a), r * std::sin(a), h * i / m;
    }
  c.F.resize(2 * m * n, 3);
  int f = 0;
  for (int i = 0; i < m; ++i)
    for (int j = 0; j < n; ++j) {
      const int a = i * n + j, b = i * n + (j + 1) % n, c0 = (i + 1) * n + j, d = (i + 1) * n + (j + 1) % n;
      c.F.row(f++) << a, c0, b;  // clockwise from outside: normals point inwards
      c.F.row(f++) << b, c0, d;
    }
  return c;
}

double NearestArc(const Eigen::MatrixXd& P, const Eigen::Vector3d& p, double* distance) {
  double best = std::numeric_limits<double>::infinity(), arc = 0.0, run = 0.0;
  for (Eigen::Index i = 0; i + 1 < P.rows(); ++i) {
    const Eigen::Vector3d a = P.row(i), b = P.row(i + 1);
    const double len = (b - a).norm();
    const double t = len > 0 ? std::clamp((p - a).dot(b - a) / (len * len), 0.0, 1.0) : 0.0;
    const double d = (a + t * (b - a) - p).norm();
    if (d < best) best = d, arc = run + t * len;
    run += len;
  }
  if (distance) *distance = best;
  return arc;
}

TriangleMesh TubeAround(const Eigen::MatrixXd& P, double radius, double grid) {
  return TubeAround(P, Eigen::VectorXd::Constant(P.rows(), radius), grid);
}

TriangleMesh TubeAround(const Eigen::MatrixXd& P, const Eigen::VectorXd& radii, double grid) {
  const double radius = radii.maxCoeff();
  const Eigen::RowVector3d lo = P.colwise().minCoeff().array() - radius - 3 * grid;
  const Eigen::RowVector3d hi = P.colwise().maxCoeff().array() + radius + 3 * grid;
  Volume<float> field;
  for (int k = 0; k < 3; ++k) field.size[k] = static_cast<std::size_t>(std::ceil((hi(k) - lo(k)) / grid)) + 1;
  field.spacing = Eigen::Vector3d::Constant(grid);
  field.origin = lo.transpose();
  field.Allocate(0.0f);
  for (std::size_t k = 0; k < field.size[2]; ++k)
    for (std::size_t j = 0; j < field.size[1]; ++j)
      for (std::size_t i = 0; i < field.size[0]; ++i) {
        // Inside where some point of the polyline is nearer than its own radius.
        const Eigen::Vector3d p = field.IndexToPhysical(Eigen::Vector3d(double(i), double(j), double(k)));
        double best = -std::numeric_limits<double>::infinity();
        for (Eigen::Index s = 0; s + 1 < P.rows(); ++s) {
          const Eigen::Vector3d a = P.row(s), b = P.row(s + 1);
          const double len2 = (b - a).squaredNorm();
          const double t = len2 > 0 ? std::clamp((p - a).dot(b - a) / len2, 0.0, 1.0) : 0.0;
          best = std::max(best, (1 - t) * radii(s) + t * radii(s + 1) - (a + t * (b - a) - p).norm());
        }
        field.At(i, j, k) = static_cast<float>(best);
      }
  vtkNew<vtkImageData> image;
  surface::ToImageData(field, image);
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->Update();
  TriangleMesh mesh = surface::FromPolyData(contour->GetOutput());
  surface::GridToPhysical(field, mesh.V);
  double volume = 0.0;
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const Eigen::Vector3d a = mesh.V.row(mesh.F(f, 0)), b = mesh.V.row(mesh.F(f, 1)), c = mesh.V.row(mesh.F(f, 2));
    volume += a.dot(b.cross(c));
  }
  if (volume > 0) mesh.F.col(1).swap(mesh.F.col(2));  // normals into the tube
  return mesh;
}

}  // namespace colonmap::realcolon::testing
