#pragma once
// Test helpers: point-to-surface distances (Surface/SurfaceDistance.h) and percentiles.
#include "Surface/SurfaceDistance.h"

#include <Eigen/Core>

#include <vector>

namespace colonmap::surface::testing {

using surface::ClosestOnSurface;
using surface::ClosestPoints;
// Value at fraction q (0..1) of the sorted values.
double Percentile(std::vector<double> values, double q);

}  // namespace colonmap::surface::testing
