#include "analysis/photo_edges.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace relight {

namespace {

// Canny's thresholds are on the gradient of the smoothed log luminance.
// Sobel's 3x3 kernel reads a step of height H as about 4 H, 0.7 of that
// after the smoothing; the gradient is stored at kGradientScale per unit.
constexpr float kGradientScale = 100.0f;
constexpr double kStepToGradient = 4 * 0.7 * kGradientScale;

float bilinear(const cv::Mat& m, float x, float y) {
  x = std::clamp(x, 0.0f, float(m.cols - 1) - 1e-3f), y = std::clamp(y, 0.0f, float(m.rows - 1) - 1e-3f);
  const int x0 = int(x), y0 = int(y);
  const float fx = x - x0, fy = y - y0;
  const float* r0 = m.ptr<float>(y0);
  const float* r1 = m.ptr<float>(std::min(y0 + 1, m.rows - 1));
  const int x1 = std::min(x0 + 1, m.cols - 1);
  return (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x1]) + fy * ((1 - fx) * r1[x0] + fx * r1[x1]);
}

}  // namespace

cv::Mat log_luminance(const Image& image) {
  cv::Mat l(image.height, image.width, CV_32F);
  double mean = 0.0;
  for (const Vec3& p : image.pixels) mean += std::max(0.0f, luminance(p));
  const float floor = std::max(1e-8f, float(1e-3 * mean / std::max<size_t>(1, image.pixels.size())));
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x)
      l.at<float>(y, x) = std::log(std::max(floor, luminance(image.pixels[size_t(y) * image.width + x])));
  return l;
}

LogLuminanceEdges log_luminance_edges(const cv::Mat& log_lum, double start_step, double continue_step) {
  cv::Mat smooth;
  cv::GaussianBlur(log_lum, smooth, cv::Size(0, 0), 1.0);
  LogLuminanceEdges e;
  cv::Sobel(smooth, e.gx, CV_32F, 1, 0);
  cv::Sobel(smooth, e.gy, CV_32F, 0, 1);
  cv::Mat dx, dy;
  e.gx.convertTo(dx, CV_16S, kGradientScale);
  e.gy.convertTo(dy, CV_16S, kGradientScale);
  cv::Canny(dx, dy, e.edges, continue_step * kStepToGradient, start_step * kStepToGradient, true);
  cv::magnitude(e.gx, e.gy, e.magnitude);
  return e;
}

Vec2 LogLuminanceEdges::normal(int x, int y) const { return Vec2(gx.at<float>(y, x), gy.at<float>(y, x)).normalized(); }

Vec2 LogLuminanceEdges::position(int x, int y) const {
  const Vec2 n = normal(x, y);
  const float m0 = magnitude.at<float>(y, x), mp = bilinear(magnitude, x + n.x(), y + n.y()),
              mm = bilinear(magnitude, x - n.x(), y - n.y());
  const float curvature = mp - 2 * m0 + mm;
  const float offset = curvature < 0 ? std::clamp(0.5f * (mm - mp) / curvature, -0.5f, 0.5f) : 0.0f;
  return Vec2(float(x), float(y)) + offset * n;
}

float EdgeField::residual(const Vec2& full, float cap) const {
  const int x = int(std::lround((full.x() - 0.5f) / scale)), y = int(std::lround((full.y() - 0.5f) / scale));
  if (x < 0 || y < 0 || x >= distance.cols || y >= distance.rows || distance.at<float>(y, x) > cap) return cap;
  const int k = nearest.at<int>(y, x);
  return std::clamp(normal[size_t(k)].dot(full - position[size_t(k)]) / scale, -cap, cap);
}

EdgeField edge_field(const cv::Mat& log_lum, int scale) {
  const LogLuminanceEdges e = log_luminance_edges(log_lum);
  EdgeField f;
  f.scale = scale;
  cv::Mat labels;
  cv::distanceTransform(e.edges == 0, f.distance, labels, cv::DIST_L2, cv::DIST_MASK_5, cv::DIST_LABEL_PIXEL);
  // Each edge pixel's own label names it.
  std::vector<int> index_of_label(size_t(e.edges.rows) * e.edges.cols + 2, -1);
  for (int y = 0; y < e.edges.rows; ++y)
    for (int x = 0; x < e.edges.cols; ++x) {
      if (!e.edges.at<uint8_t>(y, x)) continue;
      index_of_label[size_t(labels.at<int>(y, x))] = int(f.position.size());
      f.position.push_back(float(scale) * e.position(x, y) + Vec2(0.5f, 0.5f));
      f.normal.push_back(e.normal(x, y));
      f.magnitude.push_back(e.magnitude.at<float>(y, x));
    }
  f.nearest = cv::Mat(labels.size(), CV_32S);
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x)
      f.nearest.at<int>(y, x) = std::max(0, index_of_label[size_t(labels.at<int>(y, x))]);
  return f;
}

}  // namespace relight
