#include "Views/MorphSequence.h"

#include "Core/Error.h"

#include <cstdio>

namespace colonmap::views {

std::vector<double> MorphTimes(int frames) {
  if (frames < 1) throw Error("morph: at least one frame is needed");
  std::vector<double> t(static_cast<std::size_t>(frames), 0.0);
  for (int k = 1; k < frames; ++k) t[static_cast<std::size_t>(k)] = static_cast<double>(k) / (frames - 1);
  return t;
}

Eigen::MatrixXd MorphFrame(const Eigen::MatrixXd& supine, const Eigen::MatrixXd& prone, double t) {
  if (supine.rows() != prone.rows() || supine.cols() != prone.cols()) throw Error("morph: supine and prone positions differ in size");
  return (1.0 - t) * supine + t * prone;
}

Eigen::MatrixXd MorphFramingPoints(const Eigen::MatrixXd& supine, const Eigen::MatrixXd& prone) {
  if (supine.rows() != prone.rows() || supine.cols() != 3 || prone.cols() != 3) throw Error("morph: supine and prone positions differ in size");
  Eigen::MatrixXd both(2 * supine.rows(), 3);
  both << supine, prone;
  return both;
}

std::string MorphFrameName(int k, const std::string& extension) {
  if (k < 0 || k > 999) throw Error("morph: frame number out of range");
  char name[16];
  std::snprintf(name, sizeof name, "morph_%03d", k);
  return name + extension;
}

}  // namespace colonmap::views
