#include "Views/ColourMap.h"

#include "Core/Error.h"

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace colonmap::views {
namespace {

int CvMap(ColourMapKind kind) {
  switch (kind) {
    case ColourMapKind::Turbo: return cv::COLORMAP_TURBO;
    case ColourMapKind::Hsv: return cv::COLORMAP_HSV;
    case ColourMapKind::Grey: return -1;
  }
  return cv::COLORMAP_TURBO;
}

unsigned char Level(double value, double low, double high) {
  const double t = high > low ? (value - low) / (high - low) : 0.0;
  return static_cast<unsigned char>(std::lround(255.0 * std::clamp(t, 0.0, 1.0)));
}

// The colour table of a map: entry k is the colour of grey level k.
cv::Mat Table(ColourMapKind kind) {
  cv::Mat ramp(1, 256, CV_8UC1);
  for (int k = 0; k < 256; ++k) ramp.at<unsigned char>(0, k) = static_cast<unsigned char>(k);
  cv::Mat out;
  if (kind == ColourMapKind::Grey) cv::cvtColor(ramp, out, cv::COLOR_GRAY2BGR);
  else cv::applyColorMap(ramp, out, CvMap(kind));
  return out;
}

cv::Mat Wrap(ColourImage& image) { return cv::Mat(image.height, image.width, CV_8UC3, image.bgr.data()); }

}  // namespace

ColourImage::ColourImage(int w, int h, const Bgr& fill) : width(w), height(h) {
  bgr.resize(static_cast<std::size_t>(w) * h * 3);
  for (std::size_t p = 0; p < bgr.size(); p += 3) std::copy(fill.begin(), fill.end(), bgr.begin() + p);
}

Bgr ColourImage::At(int x, int y) const {
  const std::size_t o = (static_cast<std::size_t>(y) * width + x) * 3;
  return {bgr[o], bgr[o + 1], bgr[o + 2]};
}

void ColourImage::Set(int x, int y, const Bgr& c) {
  const std::size_t o = (static_cast<std::size_t>(y) * width + x) * 3;
  std::copy(c.begin(), c.end(), bgr.begin() + o);
}

Bgr ColourOf(double value, double low, double high, ColourMapKind kind, const Bgr& nanColour) {
  if (!std::isfinite(value)) return nanColour;
  const cv::Mat t = Table(kind);
  const cv::Vec3b c = t.at<cv::Vec3b>(0, Level(value, low, high));
  return {c[0], c[1], c[2]};
}

ColourImage ColourMapValues(const Eigen::MatrixXf& values, double low, double high, ColourMapKind kind,
                            const Bgr& nanColour) {
  const int rows = static_cast<int>(values.rows()), cols = static_cast<int>(values.cols());
  ColourImage out(cols, rows, nanColour);
  const cv::Mat t = Table(kind);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) {
      const float v = values(y, x);
      if (!std::isfinite(v)) continue;
      const cv::Vec3b c = t.at<cv::Vec3b>(0, Level(v, low, high));
      out.Set(x, y, {c[0], c[1], c[2]});
    }
  return out;
}

ColourImage ColourBar(int height, double low, double high, ColourMapKind kind, const std::string& title, int ticks,
                      const std::string& format, ColourBarLayout* layout) {
  height = std::max(height, 60);
  ColourImage out(110, height, {255, 255, 255});
  cv::Mat canvas = Wrap(out);
  ColourBarLayout l;
  l.barX = 8;
  l.barWidth = 18;
  l.barTop = 24;
  l.barBottom = height - 10;
  const cv::Mat t = Table(kind);
  const int n = l.barBottom - l.barTop;
  for (int r = 0; r <= n; ++r) {
    // Row barTop is `high`, row barBottom is `low`, linear in between.
    const double v = high - (high - low) * r / std::max(1, n);
    const cv::Vec3b c = t.at<cv::Vec3b>(0, Level(v, low, high));
    cv::line(canvas, cv::Point(l.barX, l.barTop + r), cv::Point(l.barX + l.barWidth - 1, l.barTop + r), cv::Scalar(c[0], c[1], c[2]), 1);
  }
  const cv::Scalar black(0, 0, 0);
  cv::rectangle(canvas, cv::Rect(l.barX - 1, l.barTop - 1, l.barWidth + 2, n + 3), black, 1);
  cv::putText(canvas, title, cv::Point(2, 14), cv::FONT_HERSHEY_SIMPLEX, 0.4, black, 1, cv::LINE_8);
  ticks = std::max(ticks, 2);
  for (int k = 0; k < ticks; ++k) {
    const double v = high - (high - low) * k / (ticks - 1.0);
    const int y = l.barTop + static_cast<int>(std::lround(n * k / (ticks - 1.0)));
    char label[48];
    std::snprintf(label, sizeof label, format.c_str(), v);
    cv::line(canvas, cv::Point(l.barX + l.barWidth + 1, y), cv::Point(l.barX + l.barWidth + 5, y), black, 1);
    cv::putText(canvas, label, cv::Point(l.barX + l.barWidth + 8, y + 4), cv::FONT_HERSHEY_SIMPLEX, 0.35, black, 1, cv::LINE_8);
  }
  if (layout) *layout = l;
  return out;
}

std::array<double, 2> QuantileRange(const std::vector<const Eigen::MatrixXf*>& images, double lowQuantile,
                                    double highQuantile) {
  std::vector<float> v;
  for (const Eigen::MatrixXf* m : images)
    for (Eigen::Index k = 0; k < m->size(); ++k)
      if (std::isfinite(m->data()[k])) v.push_back(m->data()[k]);
  if (v.empty()) throw Error("colour range: no finite values");
  std::sort(v.begin(), v.end());
  auto at = [&](double q) {
    return static_cast<double>(v[static_cast<std::size_t>(std::lround(std::clamp(q, 0.0, 1.0) * (v.size() - 1)))]);
  };
  double low = at(lowQuantile), high = at(highQuantile);
  if (!(high > low)) {
    const double pad = std::max(1e-6, 1e-3 * std::fabs(low));
    low -= pad;
    high += pad;
  }
  return {low, high};
}

std::vector<std::uint8_t> EncodePng(const ColourImage& image) {
  if (image.width < 1 || image.height < 1) throw Error("picture: empty");
  ColourImage copy = image;
  std::vector<std::uint8_t> png;
  if (!cv::imencode(".png", Wrap(copy), png)) throw Error("picture: PNG encoding failed");
  return png;
}

ColourImage DecodePng(const std::vector<std::uint8_t>& png) {
  const cv::Mat m = cv::imdecode(png, cv::IMREAD_COLOR);
  if (m.empty()) throw Error("picture: not a PNG");
  ColourImage out(m.cols, m.rows, {0, 0, 0});
  for (int y = 0; y < m.rows; ++y)
    for (int x = 0; x < m.cols; ++x) {
      const cv::Vec3b c = m.at<cv::Vec3b>(y, x);
      out.Set(x, y, {c[0], c[1], c[2]});
    }
  return out;
}

}  // namespace colonmap::views
