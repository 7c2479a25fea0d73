#include "Surface/InsideMask.h"

#include "Core/Error.h"
#include "Surface/VtkConversion.h"

#include <vtkImageData.h>
#include <vtkImageStencilToImage.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkPolyDataToImageStencil.h>

#include <algorithm>

namespace colonmap::surface {

void FillInsideMask(const TriangleMesh& closed, Volume<unsigned char>& mask) {
  if ((mask.direction - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > 1e-9)
    throw Error("inside mask: the grid must have the identity direction");
  vtkNew<vtkPolyData> pd;
  ToPolyData(closed, pd);
  vtkNew<vtkPolyDataToImageStencil> stencil;
  stencil->SetInputData(pd);
  double origin[3] = {mask.origin.x(), mask.origin.y(), mask.origin.z()};
  double spacing[3] = {mask.spacing.x(), mask.spacing.y(), mask.spacing.z()};
  stencil->SetOutputOrigin(origin);
  stencil->SetOutputSpacing(spacing);
  int extent[6] = {0, static_cast<int>(mask.size[0]) - 1, 0, static_cast<int>(mask.size[1]) - 1, 0,
                   static_cast<int>(mask.size[2]) - 1};
  stencil->SetOutputWholeExtent(extent);
  vtkNew<vtkImageStencilToImage> toImage;
  toImage->SetInputConnection(stencil->GetOutputPort());
  toImage->SetInsideValue(1);
  toImage->SetOutsideValue(0);
  toImage->SetOutputScalarTypeToUnsignedChar();
  toImage->Update();
  const unsigned char* src = static_cast<const unsigned char*>(toImage->GetOutput()->GetScalarPointer());
  mask.voxels.assign(src, src + mask.NumberOfVoxels());
}

}  // namespace colonmap::surface
