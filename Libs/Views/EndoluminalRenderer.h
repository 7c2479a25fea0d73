#pragma once
// Endoluminal (fly-through) rendering of a CT by VTK volume ray casting, what Slicer's volume
// renderer does, here on the CPU (vtkFixedPointVolumeRayCastMapper: no GPU on these machines):
// perspective camera inside the lumen, wide view angle, the endoluminal transfer function
// (VolumeRenderPreset.h), shading with a headlight. The CT is cropped to a box around the camera
// (what lies farther is hidden by the wall anyway) so that a 512 x 512 view takes well under a
// second. Rendering is in the image's own axis-aligned frame (direction cosines applied to the
// camera instead of the volume, so oblique CTs render right; a left-handed direction matrix is
// undone by mirroring the picture).
//
// Needs an X display (Debian's VTK 9.1 renders through GLX only: no EGL/OSMesa window): run
// under `xvfb-run -a`. Without one the constructor throws colonmap::Error (VTK itself would
// abort the process). VTK headers only in the .cxx.
#include "Core/Cancel.h"
#include "Core/Volume.h"
#include "Views/CameraPose.h"
#include "Views/EndoluminalImage.h"
#include "Views/VolumeRenderPreset.h"

#include <memory>
#include <mutex>
#include <string>

namespace colonmap::views {

struct EndoluminalRenderOptions {
  int width = 512, height = 512;
  double viewAngleDeg = 100;       // vertical view angle of the perspective camera
  double sampleDistanceMm = 0;     // ray step; 0: half the smallest voxel spacing
  double cropRadiusMm = 60;        // half size of the box of CT rendered, centred half a radius ahead
  std::string preset = "endoluminal";
};

// True when an X display can be opened; else false with the reason in *why.
bool RenderDisplayAvailable(std::string* why);
// An X connection (Display*) for one render window, opened with retries; null with the reason in
// *why when there is none. Given to VTK with SetDisplayId, closed after the window is gone.
void* OpenRenderDisplay(std::string* why);
void CloseRenderDisplay(void* display);
// The same, throwing colonmap::Error "<what>: <why>; ..." when there is no display.
void* OpenRenderDisplayOrThrow(const std::string& what);

// Held while a render window is set up (its X window and OpenGL context) or torn down: VTK's X
// window creation swaps the process's Xlib error handler and tries context versions with a
// shared flag, so two threads doing it at once could exit the process on a driver that refuses
// the first version (ColonSupineProne renders the flat and the endoluminal views side by side).
std::mutex& RenderWindowSetupMutex();

// Owns one such connection (declare it before the render window, so it outlives it).
struct RenderDisplay {
  void* display = nullptr;
  RenderDisplay() = default;
  RenderDisplay(const RenderDisplay&) = delete;
  RenderDisplay& operator=(const RenderDisplay&) = delete;
  ~RenderDisplay() { CloseRenderDisplay(display); }
};

class EndoluminalRenderer {
 public:
  // Throws colonmap::Error for bad options, an unknown preset or no X display.
  explicit EndoluminalRenderer(const EndoluminalRenderOptions& options);
  ~EndoluminalRenderer();
  EndoluminalRenderer(const EndoluminalRenderer&) = delete;
  EndoluminalRenderer& operator=(const EndoluminalRenderer&) = delete;

  // One view of `ct` (HU) from `camera` (LPS mm). Throws colonmap::Error (naming `what`) when the
  // camera lies outside the CT. `progress` (optional) is this picture's: it hears from inside
  // the rendering (the gradient pass, then the ray casting, some 20-50 ms apart at clinical
  // size), and a Cancelled it throws stops the picture there and leaves Render as Cancelled.
  RgbImage Render(const Volume<short>& ct, const CameraPose& camera, const std::string& what,
                  ProgressSink* progress = nullptr);

  const EndoluminalRenderOptions& Options() const { return options_; }

 private:
  struct Impl;
  EndoluminalRenderOptions options_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace colonmap::views
