#include "Surface/SurfaceDistance.h"

#include <vtkCellArray.h>
#include <vtkGenericCell.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkStaticCellLocator.h>

#include <cmath>

namespace colonmap::surface {

ClosestPoints ClosestOnSurface(const Eigen::MatrixXd& V, const Eigen::MatrixXi& F, const Eigen::MatrixXd& Q) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  for (Eigen::Index i = 0; i < V.rows(); ++i) points->InsertNextPoint(V(i, 0), V(i, 1), V(i, 2));
  vtkNew<vtkCellArray> polys;
  for (Eigen::Index f = 0; f < F.rows(); ++f) {
    const vtkIdType ids[3] = {F(f, 0), F(f, 1), F(f, 2)};
    polys->InsertNextCell(3, ids);
  }
  vtkNew<vtkPolyData> poly;
  poly->SetPoints(points);
  poly->SetPolys(polys);
  vtkNew<vtkStaticCellLocator> locator;
  locator->SetDataSet(poly);
  locator->BuildLocator();
  ClosestPoints out;
  out.distance.resize(Q.rows());
  out.point.resize(Q.rows(), 3);
  out.cell.resize(static_cast<std::size_t>(Q.rows()));
  vtkNew<vtkGenericCell> cell;
  for (Eigen::Index i = 0; i < Q.rows(); ++i) {
    double x[3] = {Q(i, 0), Q(i, 1), Q(i, 2)}, c[3], d2;
    vtkIdType id;
    int sub;
    locator->FindClosestPoint(x, c, cell, id, sub, d2);
    out.distance(i) = std::sqrt(d2);
    out.point.row(i) << c[0], c[1], c[2];
    out.cell[static_cast<std::size_t>(i)] = id;
  }
  return out;
}

}  // namespace colonmap::surface
