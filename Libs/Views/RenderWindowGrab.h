#pragma once
// The picture of an off-screen VTK render window, as RGB bytes with the top row first (VTK gives
// the bottom row first). Shared by the endoluminal and the surface renderers. No VTK header here.
#include <string>
#include <vector>

class vtkRenderWindow;

namespace colonmap::views {

// Renders nothing: reads what the last Render() drew. Throws colonmap::Error (`what` names the
// picture) when the window's size is not width x height.
std::vector<unsigned char> GrabRgbTopRowFirst(vtkRenderWindow* window, int width, int height, const std::string& what);

}  // namespace colonmap::views
