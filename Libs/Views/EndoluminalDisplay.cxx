// The X display check of EndoluminalRenderer.h, apart from every Eigen/VTK header: Xlib.h
// defines macros (Success, Status, None, Bool) that clash with them.
#include "Core/Error.h"

#include <X11/Xlib.h>

#include <chrono>
#include <cstdlib>
#include <mutex>
#include <string>
#include <thread>

namespace colonmap::views {

std::mutex& RenderWindowSetupMutex() {
  static std::mutex mutex;
  return mutex;
}

void* OpenRenderDisplay(std::string* why) {
  const char* name = std::getenv("DISPLAY");
  if (name == nullptr || *name == '\0') {
    if (why) *why = "no X display (DISPLAY is not set)";
    return nullptr;
  }
  // Xvfb now and then refuses a connection while clients come and go (measured: 10 of 600 rapid
  // opens failed), and VTK aborts the process when its own open fails: retry here, then hand
  // the connection to VTK.
  for (int attempt = 0; attempt < 40; ++attempt) {
    {
      const std::lock_guard<std::mutex> lock(RenderWindowSetupMutex());  // Xlib's globals
      if (Display* display = XOpenDisplay(nullptr)) return display;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(25));
  }
  if (why) *why = std::string("cannot open the X display '") + name + "'";
  return nullptr;
}

void CloseRenderDisplay(void* display) {
  if (!display) return;
  const std::lock_guard<std::mutex> lock(RenderWindowSetupMutex());
  XCloseDisplay(static_cast<Display*>(display));
}

void* OpenRenderDisplayOrThrow(const std::string& what) {
  std::string why;
  void* display = OpenRenderDisplay(&why);
  if (!display) throw Error(what + ": " + why + "; VTK here renders through X (GLX): run under xvfb-run -a");
  return display;
}

bool RenderDisplayAvailable(std::string* why) {
  void* display = OpenRenderDisplay(why);
  CloseRenderDisplay(display);
  return display != nullptr;
}

}  // namespace colonmap::views
