#include "Views/MorphSequence.h"

#include "Core/Error.h"

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

}  // namespace colonmap::views
