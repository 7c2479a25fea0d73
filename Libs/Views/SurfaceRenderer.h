#pragma once
// Off-screen VTK rendering of a surface (issue 8, paper Figs. 11-12: distortion colour maps and
// textures on the 3D colon, the morph frames): vtkPolyDataMapper with the scene's face colours
// (direct RGB, no lookup table, so the colours are exactly the colour bar's) or its texture tile
// (nearest-pixel lookup, repeating), smooth shading with the scene's normals, one headlight,
// two-sided lighting (the colon is seen from outside; normals may point either way), a parallel
// projection from SurfaceCamera, no multisampling. Same scene and camera give the same bytes.
//
// Needs an X display (Debian's VTK renders through GLX): without one the constructor throws
// colonmap::Error (RenderDisplayAvailable, EndoluminalRenderer.h); VTK itself would abort.
// VTK headers only in the .cxx.
#include "Views/ColourMap.h"
#include "Views/SurfaceCamera.h"
#include "Views/SurfaceScene.h"

#include <memory>

namespace colonmap::views {

struct SurfaceRenderOptions {
  int width = 360, height = 480;
  Bgr background{255, 255, 255};
  double ambient = 0.3, diffuse = 0.7;  // Phong terms of the surface (no specular: no glare on the colours)
};

class SurfaceRenderer {
 public:
  // Throws colonmap::Error for a size outside 16..4096 or no X display.
  explicit SurfaceRenderer(const SurfaceRenderOptions& options);
  ~SurfaceRenderer();
  SurfaceRenderer(const SurfaceRenderer&) = delete;
  SurfaceRenderer& operator=(const SurfaceRenderer&) = delete;

  // The picture (top row first). Throws colonmap::Error for an inconsistent scene.
  ColourImage Render(const SurfaceScene& scene, const SurfaceCamera& camera);

  const SurfaceRenderOptions& Options() const { return options_; }

 private:
  struct Impl;
  SurfaceRenderOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace colonmap::views
