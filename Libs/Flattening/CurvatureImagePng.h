#pragma once
// A colour picture of a flat curvature image for people (DESIGN §2.4): the image through a
// perceptual colour map (OpenCV's TURBO), v = 0 at the bottom row, with a legend bar and its
// values on the right. Returns the encoded PNG bytes; OpenCV stays out of this header.
#include "Core/Volume.h"

#include <cstdint>
#include <string>
#include <vector>

namespace colonmap::flattening {

struct ColourImageOptions {
  double lowQuantile = 0.01, highQuantile = 0.99;  // colour range from these quantiles
  std::string title = "H (1/mm)";
  int minimumHeight = 240;  // pixels; short images are magnified (nearest) to at least this
};

// image: nx x ny x 1 floats. low, high receive the value range mapped to the colour bar ends.
std::vector<std::uint8_t> CurvatureImagePng(const Volume<float>& image, const ColourImageOptions& options,
                                            double* low = nullptr, double* high = nullptr);

}  // namespace colonmap::flattening
