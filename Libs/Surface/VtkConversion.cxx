#include "Surface/VtkConversion.h"

#include "Core/Cancel.h"

#include <vtkCellArray.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>

#include <algorithm>
#include <vector>

namespace colonmap::surface {

void ToImageData(const Volume<float>& volume, vtkImageData* image) {
  image->SetDimensions(static_cast<int>(volume.size[0]), static_cast<int>(volume.size[1]),
                       static_cast<int>(volume.size[2]));
  image->SetSpacing(volume.spacing.x(), volume.spacing.y(), volume.spacing.z());
  image->SetOrigin(0.0, 0.0, 0.0);
  vtkNew<vtkFloatArray> scalars;
  scalars->SetNumberOfComponents(1);
  // save = 1: VTK reads the caller's voxels and never frees them (no copy of a CT-sized array).
  scalars->SetArray(const_cast<float*>(volume.voxels.data()), static_cast<vtkIdType>(volume.voxels.size()), 1);
  scalars->SetName("Scalars");
  image->GetPointData()->SetScalars(scalars);
}

void FromImageData(vtkImageData* image, Volume<float>& volume, ProgressSink* progress) {
  auto* scalars = vtkFloatArray::SafeDownCast(image->GetPointData()->GetScalars());
  volume.voxels.resize(volume.NumberOfVoxels());
  CopyReporting(scalars->GetPointer(0), volume.voxels.size(), volume.voxels.data(), progress);
}

void ToPolyData(const TriangleMesh& mesh, vtkPolyData* polyData) {
  vtkNew<vtkPoints> points;
  points->SetDataTypeToDouble();
  points->SetNumberOfPoints(mesh.V.rows());
  for (Eigen::Index i = 0; i < mesh.V.rows(); ++i) points->SetPoint(i, mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2));
  vtkNew<vtkCellArray> polys;
  polys->AllocateExact(mesh.F.rows(), 3 * mesh.F.rows());
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f) {
    const vtkIdType ids[3] = {mesh.F(f, 0), mesh.F(f, 1), mesh.F(f, 2)};
    polys->InsertNextCell(3, ids);
  }
  polyData->SetPoints(points);
  polyData->SetPolys(polys);
}

TriangleMesh FromPolyData(vtkPolyData* polyData) {
  TriangleMesh mesh;
  const vtkIdType n = polyData->GetNumberOfPoints();
  mesh.V.resize(n, 3);
  for (vtkIdType i = 0; i < n; ++i) {
    double p[3];
    polyData->GetPoint(i, p);
    mesh.V.row(i) << p[0], p[1], p[2];
  }
  std::vector<int> faces;
  vtkCellArray* polys = polyData->GetPolys();
  if (polys) {
    faces.reserve(static_cast<std::size_t>(polys->GetNumberOfCells()) * 3);
    vtkNew<vtkIdList> ids;
    for (polys->InitTraversal(); polys->GetNextCell(ids);)
      for (vtkIdType k = 1; k + 1 < ids->GetNumberOfIds(); ++k)
        for (vtkIdType c : {vtkIdType(0), k, k + 1}) faces.push_back(static_cast<int>(ids->GetId(c)));
  }
  mesh.F.resize(static_cast<Eigen::Index>(faces.size() / 3), 3);
  for (std::size_t f = 0; f < faces.size() / 3; ++f)
    for (int k = 0; k < 3; ++k) mesh.F(static_cast<Eigen::Index>(f), k) = faces[3 * f + k];
  return mesh;
}

}  // namespace colonmap::surface
