#include "Views/EndoluminalImage.h"

#include "Core/Error.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace colonmap::views {

namespace {

// A view of the bytes as an OpenCV image (RGB order kept; converted to BGR only for the codec).
cv::Mat Wrap(RgbImage& image) { return cv::Mat(image.height, image.width, CV_8UC3, image.rgb.data()); }

cv::Scalar Colour(const Rgb& c) { return cv::Scalar(c[0], c[1], c[2]); }

}  // namespace

void DrawMarker(RgbImage& image, const Eigen::Vector2d& pixel, const Rgb& colour, const std::string& text, int radius) {
  if (image.rgb.empty()) return;
  cv::Mat m = Wrap(image);
  // Fixed-point centre (4 fractional bits) keeps sub-pixel positions without randomness.
  const cv::Point centre(static_cast<int>(std::lround(pixel(0) * 16)), static_cast<int>(std::lround(pixel(1) * 16)));
  cv::circle(m, centre, radius * 16, cv::Scalar(0, 0, 0), 4, cv::LINE_AA, 4);
  cv::circle(m, centre, radius * 16, Colour(colour), 2, cv::LINE_AA, 4);
  if (!text.empty()) {
    const cv::Point at(static_cast<int>(std::lround(pixel(0))) + radius + 3, static_cast<int>(std::lround(pixel(1))) + 5);
    cv::putText(m, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
    cv::putText(m, text, at, cv::FONT_HERSHEY_SIMPLEX, 0.45, Colour(colour), 1, cv::LINE_AA);
  }
}

void DrawViewAxisCross(RgbImage& image, const Rgb& colour) {
  if (image.rgb.empty()) return;
  cv::Mat m = Wrap(image);
  const int cx = image.width / 2, cy = image.height / 2, r = std::max(3, image.width / 64);
  cv::line(m, {cx - r, cy}, {cx + r, cy}, Colour(colour), 1, cv::LINE_8);
  cv::line(m, {cx, cy - r}, {cx, cy + r}, Colour(colour), 1, cv::LINE_8);
}

RgbImage SideBySide(const RgbImage& left, const std::string& leftTitle, const RgbImage& right,
                    const std::string& rightTitle, int titleHeight) {
  if (left.width != right.width || left.height != right.height) throw Error("side-by-side views: sizes differ");
  RgbImage out;
  out.width = 2 * left.width;
  out.height = left.height + titleHeight;
  out.rgb.assign(static_cast<std::size_t>(out.width) * out.height * 3, 0);
  cv::Mat m = Wrap(out);
  RgbImage l = left, r = right;
  Wrap(l).copyTo(m(cv::Rect(0, titleHeight, left.width, left.height)));
  Wrap(r).copyTo(m(cv::Rect(left.width, titleHeight, left.width, left.height)));
  const double scale = std::clamp(titleHeight / 40.0, 0.35, 0.8);
  const int baseline = titleHeight - std::max(4, titleHeight / 4);
  cv::putText(m, leftTitle, {6, baseline}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1, cv::LINE_AA);
  cv::putText(m, rightTitle, {left.width + 6, baseline}, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255), 1,
              cv::LINE_AA);
  // A separator between the two views.
  cv::line(m, {left.width, 0}, {left.width, out.height - 1}, cv::Scalar(90, 90, 90), 1, cv::LINE_8);
  return out;
}

void WritePng(const RgbImage& image, const std::string& path, const std::string& what) {
  RgbImage copy = image;
  cv::Mat bgr;
  cv::cvtColor(Wrap(copy), bgr, cv::COLOR_RGB2BGR);
  bool ok = false;
  try {
    ok = cv::imwrite(path, bgr, {cv::IMWRITE_PNG_COMPRESSION, 6});
  } catch (const cv::Exception& e) {
    throw InputError(what, path, std::string("cannot write PNG: ") + e.what());
  }
  if (!ok) throw InputError(what, path, "cannot write PNG");
}

RgbImage ReadPng(const std::string& path, const std::string& what) {
  const cv::Mat bgr = cv::imread(path, cv::IMREAD_COLOR);
  if (bgr.empty()) throw InputError(what, path, "cannot read the image");
  RgbImage out;
  out.width = bgr.cols;
  out.height = bgr.rows;
  out.rgb.resize(static_cast<std::size_t>(out.width) * out.height * 3);
  cv::Mat m = Wrap(out);
  cv::cvtColor(bgr, m, cv::COLOR_BGR2RGB);
  return out;
}

}  // namespace colonmap::views
