#pragma once
// Colour pictures of scalar fields on the flat domain (issue 8, DESIGN §2.4-2.5): values through
// one of OpenCV's colour maps, a colour bar with tick labels, PNG encoding. The picture type is
// a plain byte buffer in OpenCV's BGR order (wrapping it in a cv::Mat costs nothing), so OpenCV
// stays out of the headers. Eigen in, bytes out.
#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace colonmap::views {

using Bgr = std::array<std::uint8_t, 3>;  // blue, green, red

struct ColourImage {
  int width = 0, height = 0;
  std::vector<std::uint8_t> bgr;  // height rows of width pixels, top row first, 3 bytes each

  ColourImage() = default;
  ColourImage(int w, int h, const Bgr& fill);
  Bgr At(int x, int y) const;
  void Set(int x, int y, const Bgr& c);
};

enum class ColourMapKind {
  Turbo,  // sequential, perceptual (curvature, dilatation)
  Hsv,    // cyclic (angles: theta and theta + pi look the same)
  Grey,
};

// The colour of `value` on the map, `low` and `high` at the two ends (values beyond are clamped).
// The map is quantised to 256 levels, as cv::applyColorMap does. NaN gets `nanColour`.
Bgr ColourOf(double value, double low, double high, ColourMapKind kind, const Bgr& nanColour = {255, 255, 255});

// values: rows x cols, row 0 drawn at the top; NaN pixels get `nanColour` (outside the domain).
ColourImage ColourMapValues(const Eigen::MatrixXf& values, double low, double high, ColourMapKind kind,
                            const Bgr& nanColour = {255, 255, 255});

// Where the bar itself lies in a ColourBar picture: pixel rows barTop (colour of `high`) down to
// barBottom (colour of `low`), columns barX .. barX + barWidth - 1.
struct ColourBarLayout {
  int barX = 0, barTop = 0, barBottom = 0, barWidth = 0;
};

// A vertical colour bar of total height `height` (>= 60 px) with a title above and `ticks`
// labelled values from high (top) to low (bottom), on white. `format` is a printf format for the
// labels (e.g. "%.3f").
ColourImage ColourBar(int height, double low, double high, ColourMapKind kind, const std::string& title, int ticks = 5,
                      const std::string& format = "%.3f", ColourBarLayout* layout = nullptr);

// The [low, high] range from quantiles of the finite values of all `images` (pooled), so that a
// few extreme pixels do not wash out the map; high > low always (a constant field gets a small
// range around its value). Throws colonmap::Error when no value is finite.
std::array<double, 2> QuantileRange(const std::vector<const Eigen::MatrixXf*>& images, double lowQuantile,
                                    double highQuantile);

// PNG bytes of the picture (deterministic: same picture, same bytes).
std::vector<std::uint8_t> EncodePng(const ColourImage& image);
// The picture back from PNG bytes (for tests and for reading pictures other modules wrote).
ColourImage DecodePng(const std::vector<std::uint8_t>& png);

}  // namespace colonmap::views
