#pragma once
// Summary statistics of registration errors (DESIGN §2.6): mean, median, 90th percentile, max.
#include <vector>

namespace colonmap::registration {

struct ErrorSummary {
  long count = 0;
  double mean = 0.0, median = 0.0, p90 = 0.0, max = 0.0;
};

// Percentiles by linear interpolation between order statistics; an empty list gives count 0.
ErrorSummary SummarizeErrors(std::vector<double> errors);

}  // namespace colonmap::registration
