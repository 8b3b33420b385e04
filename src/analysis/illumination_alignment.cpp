#include "analysis/illumination_alignment.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace relight {

namespace {

constexpr float kAlignedPx = 1.0f;              // a motion this small moves nothing (Canny places an edge to a pixel)
constexpr float kMaxMismatchShare = 1 / 80.0f;  // of the width (8 pixels of 640): the farthest match looked for
constexpr float kBandMarginPx = 2.0f;           // the band reaches this beyond the photo's edge: the edges' own blur
constexpr float kSameDirection = 0.87f;         // cos 30 degrees, between the two edges' gradients
constexpr float kSameStep = 2.0f;               // the most the two edges' gradients may differ by, as a factor
// The illumination's edges that matter: a step of 0.4 in log luminance (the
// light 1.5 times as bright on one side) starts one, 0.15 continues it; a
// misplaced edge of less contrast leaves lines of less than that in the
// albedo. Shorter than kMinEdgePixels, an edge is the render's noise.
constexpr double kIlluminationStartStep = 0.4, kIlluminationContinueStep = 0.15;
constexpr int kMinEdgePixels = 12;
// An edge is moved only where its match agrees with the image's motion to this.
constexpr float kMotionTolerancePx = 1.0f;
constexpr float kMotionHuberPx = 1.0f;
constexpr int kMotionIterations = 10;

// How the photo's edges lie from the illumination's over the whole image:
// the image motion of a camera turned, zoomed or shifted a little, to first
// order a shift, a scale and a turn about the centre: v(x) = (a0 + a2 u -
// a3 t, a1 + a2 t + a3 u) in coordinates u, t centred and scaled by half the
// width. A match that disagrees with it (a texture edge running beside an
// edge the photo does not show) is no mismatch of the camera's.
struct ImageMotion {
  Eigen::Vector4d a = Eigen::Vector4d::Zero();
  double cx = 0, cy = 0, scale = 1;

  Eigen::Matrix<double, 2, 4> basis(int x, int y) const {
    const double u = (x - cx) / scale, t = (y - cy) / scale;
    Eigen::Matrix<double, 2, 4> b;
    b << 1, 0, u, -t,  //
        0, 1, t, u;
    return b;
  }
  float across(const IlluminationAlignment::EdgeMatch& m) const {
    return float(m.normal.cast<double>().transpose() * basis(m.x, m.y) * a);
  }
  // Over the image, the longest motion: at a corner (it is affine).
  float largest(int w, int h) const {
    double most = 0.0;
    for (const auto& [x, y] : {std::pair{0, 0}, {w - 1, 0}, {0, h - 1}, {w - 1, h - 1}})
      most = std::max(most, (basis(x, y) * a).norm());
    return float(most);
  }
};

// Iteratively reweighted least squares (Huber) on the matches' offsets
// across their edges, from no motion.
ImageMotion fit_image_motion(const std::vector<IlluminationAlignment::EdgeMatch>& matches, int w, int h) {
  ImageMotion motion;
  motion.cx = 0.5 * w, motion.cy = 0.5 * h, motion.scale = 0.5 * w;
  if (matches.size() < 16) return motion;
  for (int it = 0; it < kMotionIterations; ++it) {
    Eigen::Matrix4d normal_matrix = 1e-6 * Eigen::Matrix4d::Identity();
    Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
    for (const auto& m : matches) {
      const Eigen::Matrix<double, 1, 4> j = m.normal.cast<double>().transpose() * motion.basis(m.x, m.y);
      const double r = std::abs(double(motion.across(m)) - m.offset);
      const double weight = r <= kMotionHuberPx ? 1.0 : kMotionHuberPx / r;
      normal_matrix += weight * j.transpose() * j;
      rhs += weight * j.transpose() * double(m.offset);
    }
    motion.a = normal_matrix.ldlt().solve(rhs);
  }
  return motion;
}

// Pixel indices, clamped to the image.
Vec3 bilinear(const Image& image, float x, float y) {
  x = std::clamp(x, 0.0f, float(image.width - 1)), y = std::clamp(y, 0.0f, float(image.height - 1));
  const int x0 = int(x), y0 = int(y);
  const int x1 = std::min(x0 + 1, image.width - 1), y1 = std::min(y0 + 1, image.height - 1);
  const float fx = x - float(x0), fy = y - float(y0);
  return (1 - fy) * ((1 - fx) * image.at(x0, y0) + fx * image.at(x1, y0)) +
         fy * ((1 - fx) * image.at(x0, y1) + fx * image.at(x1, y1));
}

// The edge pixels of the illumination that belong to edges of at least kMinEdgePixels.
cv::Mat long_edges(const cv::Mat& edges) {
  cv::Mat labels;
  const int count = cv::connectedComponents(edges != 0, labels, 8, CV_32S);
  std::vector<int> length(size_t(count), 0);
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x) ++length[size_t(labels.at<int>(y, x))];
  cv::Mat kept = cv::Mat::zeros(edges.size(), CV_8U);
  for (int y = 0; y < labels.rows; ++y)
    for (int x = 0; x < labels.cols; ++x)
      if (edges.at<uint8_t>(y, x) && length[size_t(labels.at<int>(y, x))] >= kMinEdgePixels) kept.at<uint8_t>(y, x) = 1;
  return kept;
}

}  // namespace

IlluminationAlignment::IlluminationAlignment(const Image& photo) : photo_edges_(edge_field(log_luminance(photo), 1)) {}

IlluminationAlignment::Moving IlluminationAlignment::moving_edges(const Image& surface_illumination) const {
  const int w = surface_illumination.width, h = surface_illumination.height;
  Moving out;
  if (photo_edges_.distance.cols != w || photo_edges_.distance.rows != h || photo_edges_.position.empty()) return out;
  const std::vector<EdgeMatch> matches = edge_matches(surface_illumination);
  const ImageMotion motion = fit_image_motion(matches, w, h);
  out.motion_px = motion.largest(w, h);
  for (const EdgeMatch& m : matches) {
    const float predicted = motion.across(m);
    if (std::abs(predicted) > kAlignedPx && std::abs(predicted - m.offset) <= kMotionTolerancePx)
      out.edges.push_back(m);
  }
  return out;
}

namespace {
// Calls at(pixel index, squared distance) for each pixel of the band a moved
// edge takes its illumination for: within its offset and kBandMarginPx.
template <typename At>
void for_band(const IlluminationAlignment::EdgeMatch& m, int w, int h, At at) {
  const float r = std::abs(m.offset) + kBandMarginPx;
  const int ri = int(std::ceil(r));
  for (int dy = -ri; dy <= ri; ++dy)
    for (int dx = -ri; dx <= ri; ++dx) {
      const int nx = m.x + dx, ny = m.y + dy;
      const float d2 = float(dx * dx + dy * dy);
      if (nx < 0 || ny < 0 || nx >= w || ny >= h || d2 > r * r) continue;
      at(size_t(ny) * w + nx, d2);
    }
}
}  // namespace

IlluminationAlignment::Mismatch IlluminationAlignment::mismatch(const Image& surface_illumination) const {
  const int w = surface_illumination.width, h = surface_illumination.height;
  const Moving moving = moving_edges(surface_illumination);
  Mismatch out{std::vector<uint8_t>(size_t(w) * h, 0), moving.motion_px};
  for (const EdgeMatch& m : moving.edges) for_band(m, w, h, [&](size_t i, float) { out.moved[i] = 1; });
  return out;
}

IlluminationAlignment::Aligned IlluminationAlignment::align(const Image& surface_illumination) const {
  const int w = surface_illumination.width, h = surface_illumination.height;
  const Moving moving = moving_edges(surface_illumination);
  Aligned out{surface_illumination, {std::vector<uint8_t>(size_t(w) * h, 0), moving.motion_px}};
  // Per pixel, the shift to take its illumination from: that of the nearest
  // illumination edge pixel whose band it lies in.
  std::vector<float> nearest(size_t(w) * h, std::numeric_limits<float>::max());
  std::vector<Vec2> shift(size_t(w) * h, Vec2::Zero());
  for (const EdgeMatch& m : moving.edges)
    for_band(m, w, h, [&](size_t i, float d2) {
      if (d2 >= nearest[i]) return;
      nearest[i] = d2;
      shift[i] = m.offset * m.normal;
    });
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (nearest[i] == std::numeric_limits<float>::max()) continue;
      out.illumination.pixels[i] = bilinear(surface_illumination, float(x) - shift[i].x(), float(y) - shift[i].y());
      out.mismatch.moved[i] = 1;
    }
  return out;
}

std::vector<IlluminationAlignment::EdgeMatch> IlluminationAlignment::edge_matches(
    const Image& surface_illumination) const {
  const int w = surface_illumination.width, h = surface_illumination.height;
  const float farthest = std::max(2 * kAlignedPx, kMaxMismatchShare * float(w));
  const LogLuminanceEdges e =
      log_luminance_edges(log_luminance(surface_illumination), kIlluminationStartStep, kIlluminationContinueStep);
  const cv::Mat edges = long_edges(e.edges);
  std::vector<EdgeMatch> matches;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (!edges.at<uint8_t>(y, x)) continue;
      if (photo_edges_.distance.at<float>(y, x) > farthest) continue;
      const size_t k = size_t(photo_edges_.nearest.at<int>(y, x));
      const Vec2 n = e.normal(x, y);
      if (n.dot(photo_edges_.normal[k]) < kSameDirection) continue;
      const float step_ratio = photo_edges_.magnitude[k] / e.magnitude.at<float>(y, x);
      if (step_ratio > kSameStep || step_ratio < 1 / kSameStep) continue;
      // Along the edge's normal only: an edge slides along itself freely.
      // (The field's positions are pixel centres' coordinates, + 0.5.)
      const Vec2 photo_edge = photo_edges_.position[k] - Vec2(0.5f, 0.5f);
      matches.push_back({x, y, n, n.dot(photo_edge - e.position(x, y))});
    }
  return matches;
}


}  // namespace relight
