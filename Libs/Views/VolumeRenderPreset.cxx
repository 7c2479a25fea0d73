#include "Views/VolumeRenderPreset.h"

#include "Core/Error.h"

namespace colonmap::views {

std::vector<std::string> EndoluminalPresetNames() { return {"endoluminal", "endoluminal-grey", "endoluminal-sharp"}; }

VolumeRenderPreset EndoluminalPreset(const std::string& name) {
  VolumeRenderPreset p;
  p.name = name;
  if (name == "endoluminal" || name == "endoluminal-sharp") {
    if (name == "endoluminal")
      p.opacity = {{-1024, 0.0}, {-700, 0.0}, {-300, 1.0}, {3071, 1.0}};
    else
      p.opacity = {{-1024, 0.0}, {-560, 0.0}, {-440, 1.0}, {3071, 1.0}};
    // Mucosa pink-orange at the air boundary, deeper red for tissue, pale for bone and contrast.
    p.colour = {{-1024, 0.90, 0.55, 0.45}, {-500, 0.93, 0.62, 0.52}, {100, 0.80, 0.35, 0.30}, {400, 0.95, 0.90, 0.80}};
    return p;
  }
  if (name == "endoluminal-grey") {
    p.opacity = {{-1024, 0.0}, {-700, 0.0}, {-300, 1.0}, {3071, 1.0}};
    p.colour = {{-1024, 0.85, 0.85, 0.85}, {3071, 0.85, 0.85, 0.85}};
    return p;
  }
  std::string known;
  for (const std::string& n : EndoluminalPresetNames()) known += (known.empty() ? "" : ", ") + n;
  throw Error("volume rendering preset '" + name + "': unknown (known: " + known + ")");
}

}  // namespace colonmap::views
