#pragma once
// Transfer functions for endoluminal volume rendering of CT colonography, as plain data (HU ->
// opacity, HU -> colour) so that the renderer (VTK, EndoluminalRenderer.cxx) and tests share
// them. Air (about -1000 HU) is transparent, the wall (soft tissue, about 40 HU) opaque, with the
// opacity ramp placed on the air-wall transition (-700..-300 HU, half way at about -500 HU, where
// the lumen surface is) so the rendered wall is where ColonSurface puts it.
#include <array>
#include <string>
#include <vector>

namespace colonmap::views {

struct VolumeRenderPreset {
  std::string name;
  std::vector<std::array<double, 2>> opacity;  // (HU, opacity 0..1), increasing HU
  std::vector<std::array<double, 4>> colour;   // (HU, r, g, b in 0..1)
  double ambient = 0.2, diffuse = 0.8, specular = 0.2, specularPower = 10.0;
};

// Known names: "endoluminal" (pink mucosa, the look of a virtual colonoscopy),
// "endoluminal-grey" (grey, for printing), "endoluminal-sharp" (narrow ramp: crisper wall,
// noisier on thin folds). Throws colonmap::Error listing the names for another one.
VolumeRenderPreset EndoluminalPreset(const std::string& name);
std::vector<std::string> EndoluminalPresetNames();

}  // namespace colonmap::views
