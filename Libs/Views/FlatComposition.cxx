#include "Views/FlatComposition.h"

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>

namespace colonmap::views {
namespace {

const Bgr kWhite{255, 255, 255};
const cv::Scalar kBlack(0, 0, 0);

cv::Mat Wrap(ColourImage& image) { return cv::Mat(image.height, image.width, CV_8UC3, image.bgr.data()); }
cv::Mat WrapConst(const ColourImage& image) {
  return cv::Mat(image.height, image.width, CV_8UC3, const_cast<std::uint8_t*>(image.bgr.data()));
}

void Paste(ColourImage& canvas, const ColourImage& picture, int x, int y) {
  if (picture.width < 1 || picture.height < 1) return;
  WrapConst(picture).copyTo(Wrap(canvas)(cv::Rect(x, y, picture.width, picture.height)));
}

}  // namespace

ColourImage StackColumn(const std::vector<ColourImage>& pictures, const std::vector<std::string>& labels,
                        const std::string& title, int gap, int labelWidth, std::vector<int>* yOffsets, int* xOffset) {
  const int titleHeight = title.empty() ? 0 : 22;
  int width = 0, height = titleHeight;
  for (const ColourImage& p : pictures) {
    width = std::max(width, p.width);
    height += p.height + gap;
  }
  int baseline = 0;
  const int titleWidth = title.empty() ? 0 : cv::getTextSize(title, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline).width;
  width = std::max(width + labelWidth + 4, titleWidth + labelWidth + 4);
  ColourImage out(std::max(width, 1), std::max(height, 1), kWhite);
  cv::Mat canvas = Wrap(out);
  if (!title.empty())
    cv::putText(canvas, title, cv::Point(labelWidth, 15), cv::FONT_HERSHEY_SIMPLEX, 0.5, kBlack, 1, cv::LINE_8);
  int y = titleHeight;
  if (yOffsets) yOffsets->clear();
  for (std::size_t k = 0; k < pictures.size(); ++k) {
    Paste(out, pictures[k], labelWidth, y);
    if (yOffsets) yOffsets->push_back(y);
    if (k < labels.size())
      cv::putText(canvas, labels[k], cv::Point(4, y + std::min(pictures[k].height, 40) / 2 + 6), cv::FONT_HERSHEY_SIMPLEX, 0.55,
                  kBlack, 1, cv::LINE_8);
    y += pictures[k].height + gap;
  }
  if (xOffset) *xOffset = labelWidth;
  return out;
}

ColourImage SideBySide(const std::vector<ColourImage>& pictures, int gap) {
  int width = 0, height = 0;
  for (const ColourImage& p : pictures) {
    width += p.width;
    height = std::max(height, p.height);
  }
  width += gap * std::max<int>(0, static_cast<int>(pictures.size()) - 1);
  ColourImage out(std::max(width, 1), std::max(height, 1), kWhite);
  int x = 0;
  for (const ColourImage& p : pictures) {
    Paste(out, p, x, 0);
    x += p.width + gap;
  }
  return out;
}

ColourImage WithCaption(const ColourImage& picture, const std::string& caption) {
  const int h = 26;
  int baseline = 0;
  const cv::Size text = cv::getTextSize(caption, cv::FONT_HERSHEY_SIMPLEX, 0.45, 1, &baseline);
  ColourImage out(std::max(picture.width, text.width + 8), picture.height + h, kWhite);
  cv::putText(Wrap(out), caption, cv::Point(4, 17), cv::FONT_HERSHEY_SIMPLEX, 0.45, kBlack, 1, cv::LINE_8);
  Paste(out, picture, 0, h);
  return out;
}

void DrawFeature(ColourImage& picture, const Eigen::Vector2d& centre, const Eigen::Vector2d& end0,
                 const Eigen::Vector2d& end1, const Bgr& colour, const std::string& label) {
  cv::Mat canvas = Wrap(picture);
  const cv::Scalar c(colour[0], colour[1], colour[2]);
  auto P = [](const Eigen::Vector2d& p) { return cv::Point(static_cast<int>(std::lround(p.x())), static_cast<int>(std::lround(p.y()))); };
  cv::line(canvas, P(end0), P(end1), kBlack, 3, cv::LINE_8);
  cv::line(canvas, P(end0), P(end1), c, 1, cv::LINE_8);
  cv::circle(canvas, P(centre), 4, kBlack, -1, cv::LINE_8);
  cv::circle(canvas, P(centre), 3, c, -1, cv::LINE_8);
  if (!label.empty())
    cv::putText(canvas, label, P(centre + Eigen::Vector2d(5, -4)), cv::FONT_HERSHEY_SIMPLEX, 0.3, c, 1, cv::LINE_8);
}

Bgr MatchColour(int k) {
  // Hue (OpenCV: 0..180) by the golden angle; full saturation and value.
  const double hue = std::fmod(k * 137.50776405, 360.0) / 2.0;
  cv::Mat hsv(1, 1, CV_8UC3, cv::Scalar(static_cast<int>(std::lround(hue)) % 180, 255, 255)), bgr;
  cv::cvtColor(hsv, bgr, cv::COLOR_HSV2BGR);
  const cv::Vec3b v = bgr.at<cv::Vec3b>(0, 0);
  return {v[0], v[1], v[2]};
}

}  // namespace colonmap::views
