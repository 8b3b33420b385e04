#include "analysis/photo_blur.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "analysis/photo_edges.h"

namespace relight {

namespace {

constexpr float kEdgeStep = 0.3f;  // in log luminance between neighbours
constexpr int kEdgeReach = 2;      // pixels either side of the step
constexpr float kCandidates[] = {0.5f, 0.75f, 1.0f, 1.5f, 2.0f};

// The pixels near a step of the illumination's log luminance that the
// geometry covers.
cv::Mat edge_band(const Image& surface, const GBuffer& g) {
  const cv::Mat l = log_luminance(surface);
  cv::Mat step(l.size(), CV_8U, cv::Scalar(0));
  for (int y = 0; y < l.rows; ++y)
    for (int x = 0; x < l.cols; ++x) {
      const float v = l.at<float>(y, x);
      const bool right = x + 1 < l.cols && std::abs(l.at<float>(y, x + 1) - v) > kEdgeStep;
      const bool below = y + 1 < l.rows && std::abs(l.at<float>(y + 1, x) - v) > kEdgeStep;
      if (right || below) step.at<uint8_t>(y, x) = 1;
    }
  cv::Mat band;
  cv::dilate(step, band, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * kEdgeReach + 1, 2 * kEdgeReach + 1)));
  for (int y = 0; y < l.rows; ++y)
    for (int x = 0; x < l.cols; ++x)
      if (g.coverage(x, y) < 0.5f) band.at<uint8_t>(y, x) = 0;
  return band;
}

// The median over `band` of |log albedo| steps to the right and below.
float roughness(const cv::Mat& log_photo, const Image& surface, const cv::Mat& band) {
  const cv::Mat log_albedo = log_photo - log_luminance(surface);
  std::vector<float> steps;
  for (int y = 0; y + 1 < band.rows; ++y)
    for (int x = 0; x + 1 < band.cols; ++x)
      if (band.at<uint8_t>(y, x)) {
        const float v = log_albedo.at<float>(y, x);
        steps.push_back(std::abs(log_albedo.at<float>(y, x + 1) - v) + std::abs(log_albedo.at<float>(y + 1, x) - v));
      }
  if (steps.empty()) return 0.0f;
  std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
  return steps[steps.size() / 2];
}

}  // namespace

Image gaussian_blur(const Image& image, float sigma_px) {
  if (!(sigma_px > 0.0f)) return image;
  cv::Mat m(image.height, image.width, CV_32FC3, const_cast<Vec3*>(image.pixels.data()));
  Image out(image.width, image.height);
  cv::Mat blurred(out.height, out.width, CV_32FC3, out.pixels.data());
  cv::GaussianBlur(m, blurred, cv::Size(0, 0), sigma_px, sigma_px, cv::BORDER_REPLICATE);
  return out;
}

Image deblur(const Image& image, float sigma_px) {
  if (!(sigma_px > 0.0f)) return image;
  const int w = image.width, h = image.height;
  // The mirrored margin keeps the transform's wrap out of the filter's reach.
  const int pad = deblur_reach_px(sigma_px);
  const int rows = cv::getOptimalDFTSize(h + 2 * pad), cols = cv::getOptimalDFTSize(w + 2 * pad);
  // The filter's gain H / (H^2 + k Lap^2) at frequency (fx, fy), from its
  // factors along each axis: H = Hx Hy, Lap = Lx + Ly.
  struct Axis {
    std::vector<float> blur, laplacian;
  };
  const auto axis = [&](int n) {
    Axis a{std::vector<float>(size_t(n)), std::vector<float>(size_t(n))};
    for (int i = 0; i < n; ++i) {
      const float f = float(i <= n / 2 ? i : i - n) / float(n), s = std::sin(kPi * f);
      a.blur[size_t(i)] = std::exp(-2.0f * kPi * kPi * sigma_px * sigma_px * f * f);
      a.laplacian[size_t(i)] = 4.0f * s * s;
    }
    return a;
  };
  const Axis along_x = axis(cols), along_y = axis(rows);
  std::vector<cv::Mat> channels;
  cv::split(cv::Mat(h, w, CV_32FC3, const_cast<Vec3*>(image.pixels.data())), channels);
  for (cv::Mat& channel : channels) {
    cv::Mat padded, spectrum;
    cv::copyMakeBorder(channel, padded, pad, rows - h - pad, pad, cols - w - pad, cv::BORDER_REFLECT);
    cv::dft(padded, spectrum, cv::DFT_COMPLEX_OUTPUT);
    padded.release();
    for (int y = 0; y < rows; ++y) {
      auto* row = spectrum.ptr<cv::Vec2f>(y);
      for (int x = 0; x < cols; ++x) {
        const float blur = along_y.blur[size_t(y)] * along_x.blur[size_t(x)];
        const float laplacian = along_y.laplacian[size_t(y)] + along_x.laplacian[size_t(x)];
        row[x] *= blur / (blur * blur + kDeblurSmoothness * laplacian * laplacian);
      }
    }
    cv::idft(spectrum, padded, cv::DFT_REAL_OUTPUT | cv::DFT_SCALE);
    channel = padded(cv::Rect(pad, pad, w, h)).clone();
  }
  Image out(w, h);
  cv::Mat merged(h, w, CV_32FC3, out.pixels.data());
  cv::merge(channels, merged);
  return out;
}

namespace {

// One part of the illumination (the surface's, weighted by the coverage, or
// the background's, by the rest) blurred with its weight and divided by the
// pixel's own; 0 where the pixel has none of it.
Image blur_part(const Image& part, const GBuffer& g, bool surface, float sigma_px) {
  const auto weight = [&](int x, int y) { return surface ? g.coverage(x, y) : 1.0f - g.coverage(x, y); };
  Image weighted(part.width, part.height);
  for (int y = 0; y < part.height; ++y)
    for (int x = 0; x < part.width; ++x) weighted.at(x, y) = weight(x, y) * part.at(x, y);
  Image blurred = gaussian_blur(weighted, sigma_px);
  for (int y = 0; y < part.height; ++y)
    for (int x = 0; x < part.width; ++x) {
      const float w = weight(x, y);
      blurred.at(x, y) = w > 0.0f ? Vec3(blurred.at(x, y) / w) : Vec3::Zero();
    }
  return blurred;
}

}  // namespace

IlluminationImages blur_illumination(const IlluminationImages& illumination, const GBuffer& g, float sigma_px) {
  return {blur_part(illumination.surface, g, true, sigma_px), blur_part(illumination.background, g, false, sigma_px)};
}

PhotoBlur measure_photo_blur(const Image& photo, const IlluminationImages& illumination, const GBuffer& g) {
  PhotoBlur blur;
  const cv::Mat band = edge_band(illumination.surface, g);
  blur.edge_pixels = size_t(cv::countNonZero(band));
  if (blur.edge_pixels == 0) return blur;
  const cv::Mat log_photo = log_luminance(photo);
  blur.roughness_sharp = blur.roughness_blurred = roughness(log_photo, illumination.surface, band);
  float best = blur.roughness_sharp, best_sigma = 0.0f;
  for (const float sigma : kCandidates) {
    const float r = roughness(log_photo, blur_part(illumination.surface, g, true, sigma), band);
    if (r < best) best = r, best_sigma = sigma;
  }
  if (best < (1.0f - kSofterShare) * blur.roughness_sharp) blur.sigma_px = best_sigma, blur.roughness_blurred = best;
  return blur;
}

}  // namespace relight
