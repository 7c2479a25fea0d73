// The X display check of EndoluminalRenderer.h, apart from every Eigen/VTK header: Xlib.h
// defines macros (Success, Status, None, Bool) that clash with them.
#include <X11/Xlib.h>

#include <cstdlib>
#include <string>

namespace colonmap::views {

bool RenderDisplayAvailable(std::string* why) {
  const char* name = std::getenv("DISPLAY");
  if (name == nullptr || *name == '\0') {
    if (why) *why = "no X display (DISPLAY is not set)";
    return false;
  }
  Display* display = XOpenDisplay(nullptr);
  if (display == nullptr) {
    if (why) *why = std::string("cannot open the X display '") + name + "'";
    return false;
  }
  XCloseDisplay(display);
  return true;
}

}  // namespace colonmap::views
