#include "Flattening/CurvatureImagePng.h"

#include "Core/Error.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace colonmap::flattening {
namespace {

std::string Label(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3f", v);
  return buf;
}

}  // namespace

std::vector<std::uint8_t> CurvatureImagePng(const Volume<float>& image, const ColourImageOptions& options,
                                            double* lowOut, double* highOut) {
  const int nx = static_cast<int>(image.size[0]), ny = static_cast<int>(image.size[1]);
  if (nx < 1 || ny < 1 || image.size[2] != 1) throw Error("curvature picture: not a 2D image");
  std::vector<float> sorted(image.voxels.begin(), image.voxels.end());
  std::sort(sorted.begin(), sorted.end());
  auto at = [&](double q) { return static_cast<double>(sorted[static_cast<std::size_t>(std::lround(q * (sorted.size() - 1)))]); };
  double low = at(options.lowQuantile), high = at(options.highQuantile);
  if (!(high > low)) high = low + 1e-6;
  if (lowOut) *lowOut = low;
  if (highOut) *highOut = high;

  // Grey levels 0..255, row 0 = top = largest v.
  cv::Mat grey(ny, nx, CV_8UC1);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double t = (image.voxels[image.Offset(i, j, 0)] - low) / (high - low);
      grey.at<unsigned char>(ny - 1 - j, i) = static_cast<unsigned char>(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
    }
  const int zoom = std::max(1, (options.minimumHeight + ny - 1) / ny);
  if (zoom > 1) cv::resize(grey, grey, cv::Size(nx * zoom, ny * zoom), 0, 0, cv::INTER_NEAREST);
  cv::Mat colour;
  cv::applyColorMap(grey, colour, cv::COLORMAP_TURBO);

  // Canvas: the picture, then a legend panel (bar + labels) on the right.
  const int h = std::max(colour.rows, options.minimumHeight), panel = 120, margin = 10;
  cv::Mat canvas(h + 2 * margin, colour.cols + panel + 2 * margin, CV_8UC3, cv::Scalar(255, 255, 255));
  colour.copyTo(canvas(cv::Rect(margin, margin, colour.cols, colour.rows)));
  const int barX = colour.cols + 2 * margin, barTop = margin + 24, barBottom = margin + h - 8, barW = 18;
  cv::Mat ramp(barBottom - barTop, 1, CV_8UC1);
  for (int r = 0; r < ramp.rows; ++r)
    ramp.at<unsigned char>(r, 0) = static_cast<unsigned char>(std::lround(255.0 * (ramp.rows - 1 - r) / std::max(1, ramp.rows - 1)));
  cv::Mat rampColour;
  cv::applyColorMap(ramp, rampColour, cv::COLORMAP_TURBO);
  cv::resize(rampColour, rampColour, cv::Size(barW, ramp.rows), 0, 0, cv::INTER_NEAREST);
  rampColour.copyTo(canvas(cv::Rect(barX, barTop, barW, ramp.rows)));
  cv::rectangle(canvas, cv::Rect(barX, barTop, barW, ramp.rows), cv::Scalar(0, 0, 0), 1);
  const cv::Scalar black(0, 0, 0);
  cv::putText(canvas, options.title, cv::Point(barX - 4, margin + 12), cv::FONT_HERSHEY_SIMPLEX, 0.4, black, 1, cv::LINE_8);
  for (int k = 0; k <= 4; ++k) {
    const double v = high - (high - low) * k / 4.0;
    const int y = barTop + static_cast<int>(std::lround((ramp.rows - 1) * k / 4.0));
    cv::line(canvas, cv::Point(barX + barW, y), cv::Point(barX + barW + 4, y), black, 1);
    cv::putText(canvas, Label(v), cv::Point(barX + barW + 7, y + 4), cv::FONT_HERSHEY_SIMPLEX, 0.35, black, 1, cv::LINE_8);
  }
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", canvas, png)) throw Error("curvature picture: PNG encoding failed");
  return png;
}

}  // namespace colonmap::flattening
