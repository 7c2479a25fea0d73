#pragma once
// The picture a linked view ends up as: an RGB image (plain bytes, rows top to bottom), markers
// for findings drawn on it, two views side by side under title bars, PNG out. OpenCV only in
// the .cxx (drawing, text, PNG codec).
#include <Eigen/Core>

#include <array>
#include <string>
#include <vector>

namespace colonmap::views {

struct RgbImage {
  int width = 0, height = 0;
  std::vector<unsigned char> rgb;  // width * height * 3, rows top to bottom
};

using Rgb = std::array<unsigned char, 3>;

// A ring (radius `radius` px) with a short label beside it at `pixel` (x right, y down); parts
// outside the image are clipped.
void DrawMarker(RgbImage& image, const Eigen::Vector2d& pixel, const Rgb& colour, const std::string& text, int radius);
// A small cross at the image centre: where the view axis points.
void DrawViewAxisCross(RgbImage& image, const Rgb& colour);

// left | right, each under a title bar of `titleHeight` px (text left-aligned, white on black);
// both images must have the same size.
RgbImage SideBySide(const RgbImage& left, const std::string& leftTitle, const RgbImage& right,
                    const std::string& rightTitle, int titleHeight = 24);

// Throws colonmap::InputError(what, path, ...) when the file cannot be written / read.
void WritePng(const RgbImage& image, const std::string& path, const std::string& what);
RgbImage ReadPng(const std::string& path, const std::string& what);

}  // namespace colonmap::views
