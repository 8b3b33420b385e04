// Order statistics of measurements (frame times).
#pragma once

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace relight {

// The smallest value that `share` (0..1] of the values are at most: the
// median for 0.5, the 95th percentile for 0.95.
inline double percentile(std::vector<double> values, double share) {
  if (values.empty()) throw std::invalid_argument("percentile of no values");
  std::sort(values.begin(), values.end());
  const size_t rank = size_t(std::max(1.0, std::ceil(share * double(values.size()))));
  return values[std::min(rank, values.size()) - 1];
}

}  // namespace relight
