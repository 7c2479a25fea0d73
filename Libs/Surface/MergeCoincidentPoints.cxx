#include "Surface/MergeCoincidentPoints.h"

#include "Surface/VtkConversion.h"

#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkStaticPointLocator.h>

namespace colonmap::surface {

TriangleMesh MergeCoincidentPoints(const TriangleMesh& mesh, double tolerance, std::vector<int>* mergedInto) {
  const Eigen::Index n = mesh.V.rows();
  std::vector<int> into(static_cast<std::size_t>(n), -1);  // representative (input index) of each point
  if (n > 0) {
    vtkNew<vtkPolyData> cloud;
    ToPolyData(mesh, cloud);
    vtkNew<vtkStaticPointLocator> locator;  // its queries are thread-safe and exact; only its merge races
    locator->SetDataSet(cloud);
    locator->BuildLocator();
    vtkNew<vtkIdList> near;
    for (Eigen::Index i = 0; i < n; ++i) {
      if (into[static_cast<std::size_t>(i)] >= 0) continue;
      into[static_cast<std::size_t>(i)] = static_cast<int>(i);
      const double x[3] = {mesh.V(i, 0), mesh.V(i, 1), mesh.V(i, 2)};
      locator->FindPointsWithinRadius(tolerance, x, near);
      for (vtkIdType k = 0; k < near->GetNumberOfIds(); ++k) {
        const vtkIdType j = near->GetId(k);
        if (j > i && into[static_cast<std::size_t>(j)] < 0) into[static_cast<std::size_t>(j)] = static_cast<int>(i);
      }
    }
  }
  // Representatives numbered in order.
  std::vector<int> newIndex(static_cast<std::size_t>(n), -1);
  int kept = 0;
  for (Eigen::Index i = 0; i < n; ++i)
    if (into[static_cast<std::size_t>(i)] == static_cast<int>(i)) newIndex[static_cast<std::size_t>(i)] = kept++;
  TriangleMesh out;
  out.V.resize(kept, 3);
  for (Eigen::Index i = 0; i < n; ++i)
    if (newIndex[static_cast<std::size_t>(i)] >= 0) out.V.row(newIndex[static_cast<std::size_t>(i)]) = mesh.V.row(i);
  out.F.resize(mesh.F.rows(), 3);
  for (Eigen::Index f = 0; f < mesh.F.rows(); ++f)
    for (int c = 0; c < 3; ++c)
      out.F(f, c) = newIndex[static_cast<std::size_t>(into[static_cast<std::size_t>(mesh.F(f, c))])];
  if (mergedInto) {
    mergedInto->resize(static_cast<std::size_t>(n));
    for (Eigen::Index i = 0; i < n; ++i)
      (*mergedInto)[static_cast<std::size_t>(i)] = newIndex[static_cast<std::size_t>(into[static_cast<std::size_t>(i)])];
  }
  return out;
}

}  // namespace colonmap::surface
