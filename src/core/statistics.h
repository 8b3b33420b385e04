// Order statistics of measurements (frame times), and the blocks of an
// image a jackknife leaves out in turn.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// The jackknife block of pixel (x, y) of an image `width` wide: squares a
// tenth of the width, so that a fit over pixels near each other (one
// surface, one edge) is left out whole and its standard error sees how far
// apart they are, whatever the photo's size.
inline constexpr int kJackknifeBlocksPerWidth = 10;
inline uint32_t jackknife_block(int x, int y, int width) {
  const int block = std::max(1, width / kJackknifeBlocksPerWidth), across = (width + block - 1) / block;
  return uint32_t((y / block) * across + x / block);
}

}  // namespace relight
