#pragma once
// Composition of flat-view pictures (issue 8, paper Figs. 9, 12, 13): segment pictures stacked
// into a column with their labels, columns side by side under titles, a legend beside them, and
// feature markers drawn onto a segment picture. Pictures are views::ColourImage (OpenCV only in
// the .cxx).
#include "Views/ColourMap.h"

#include <Eigen/Core>

#include <string>
#include <vector>

namespace colonmap::views {

// One column: `title` on top, then the pictures top to bottom, each with its label to the left,
// `gap` white pixels between them. Pictures narrower than the widest are left-aligned. The
// column's left margin (labels) is `labelWidth` pixels. yOffsets (optional) receives the row of
// each picture's top edge in the column, xOffset the column of their left edge.
ColourImage StackColumn(const std::vector<ColourImage>& pictures, const std::vector<std::string>& labels,
                        const std::string& title, int gap = 10, int labelWidth = 24, std::vector<int>* yOffsets = nullptr,
                        int* xOffset = nullptr);

// Pictures next to each other, top-aligned, `gap` white pixels between, white below shorter ones.
ColourImage SideBySide(const std::vector<ColourImage>& pictures, int gap = 16);

// A line of text added above the picture (caption of the whole figure).
ColourImage WithCaption(const ColourImage& picture, const std::string& caption);

// A fold feature on a segment picture: a circle at `centre` and the principal-axis segment
// from `end0` to `end1` (pixel coordinates, x right, y down), in `colour`; `label` (may be
// empty) written beside the circle.
void DrawFeature(ColourImage& picture, const Eigen::Vector2d& centre, const Eigen::Vector2d& end0,
                 const Eigen::Vector2d& end1, const Bgr& colour, const std::string& label);

// A distinct, deterministic colour for match number k (hues spread by the golden angle, fully
// saturated, never grey).
Bgr MatchColour(int k);

}  // namespace colonmap::views
