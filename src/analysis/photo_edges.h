// An image's edges, as registration and the albedo's trust in the division
// find them: Canny on the gradient of the smoothed log luminance (by default
// a step of 0.15 in log luminance, a 16 % contrast, starts an edge, 0.06
// continues it), so that an edge is a ratio of brightness, the same in
// shadow and in sunlight.
#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "core/image.h"

namespace relight {

// Log luminance per pixel, CV_32F; dark pixels floored at 1/1000 of the
// image's mean luminance.
cv::Mat log_luminance(const Image& image);

struct LogLuminanceEdges {
  cv::Mat edges;              // CV_8U, non-zero on an edge pixel
  cv::Mat gx, gy, magnitude;  // CV_32F, the smoothed log luminance's gradient

  Vec2 normal(int x, int y) const;  // unit, towards the brighter side
  // Edge pixel (x, y)'s edge to a fraction of a pixel, in pixel indices: the
  // peak of the gradient across it (a parabola through three samples).
  Vec2 position(int x, int y) const;
};
LogLuminanceEdges log_luminance_edges(const cv::Mat& log_lum, double start_step = 0.15, double continue_step = 0.06);

// One level of registration's pyramid: the photo's edges, each to a fraction
// of a pixel (the peak of the gradient across it) with its normal, and for
// every pixel the nearest of them. The residual of an image position is its
// distance across the nearest edge (point to line: it slides along the edge
// freely), in this level's pixels; `scale` full-resolution pixels make one of
// them. Level pixel i is centred on full-resolution position scale * i + 0.5
// (pyrDown keeps the even pixels' centres).
struct EdgeField {
  int scale = 1;
  cv::Mat distance;                    // CV_32F, to the nearest edge pixel, this level's pixels
  cv::Mat nearest;                     // CV_32S, the nearest edge pixel's index in position/normal
  std::vector<Vec2> position, normal;  // full-resolution image positions; unit
  std::vector<float> magnitude;        // the log-luminance gradient there, this level's

  size_t edge_pixels() const { return position.size(); }
  // Signed, within +-cap; cap where no edge is within cap (or outside the photo).
  float residual(const Vec2& full, float cap) const;
};

// `log_lum` is the level's log luminance, `scale` its pixel in full-resolution pixels.
EdgeField edge_field(const cv::Mat& log_lum, int scale);

}  // namespace relight
