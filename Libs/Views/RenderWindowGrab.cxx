#include "Views/RenderWindowGrab.h"

#include "Core/Error.h"

#include <vtkImageData.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkWindowToImageFilter.h>

#include <algorithm>
#include <cstddef>

namespace colonmap::views {

std::vector<unsigned char> GrabRgbTopRowFirst(vtkRenderWindow* window, int width, int height, const std::string& what) {
  vtkNew<vtkWindowToImageFilter> grab;
  grab->SetInput(window);
  grab->SetInputBufferTypeToRGB();
  grab->ReadFrontBufferOff();
  grab->Update();
  vtkImageData* shot = grab->GetOutput();
  int dims[3];
  shot->GetDimensions(dims);
  if (dims[0] != width || dims[1] != height) throw Error(what + ": the render window has the wrong size");
  const unsigned char* src = static_cast<const unsigned char*>(shot->GetScalarPointer());
  const std::size_t row = static_cast<std::size_t>(width) * 3;
  std::vector<unsigned char> rgb(row * height);
  for (int y = 0; y < height; ++y) std::copy(src + (height - 1 - y) * row, src + (height - y) * row, rgb.data() + y * row);
  return rgb;
}

}  // namespace colonmap::views
