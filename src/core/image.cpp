#include "core/image.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace relight {

double psnr(const Image& test, const Image& reference, const std::vector<float>* weight) {
  if (test.width != reference.width || test.height != reference.height)
    throw std::invalid_argument("psnr: images differ in size");
  double sum = 0.0, wsum = 0.0;
  for (size_t i = 0; i < test.size(); ++i) {
    const double w = weight ? (*weight)[i] : 1.0;
    if (w <= 0.0) continue;
    const Vec3 d = test.pixels[i] - reference.pixels[i];
    sum += w * double(d.squaredNorm()) / 3.0;
    wsum += w;
  }
  if (wsum == 0.0) return 0.0;
  const double mse = sum / wsum;
  if (mse <= 0.0) return std::numeric_limits<double>::infinity();
  return 10.0 * std::log10(1.0 / mse);
}

float srgb_encode(float v) {
  v = std::clamp(v, 0.0f, 1.0f);
  return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1.0f / 2.4f) - 0.055f;
}

float srgb_decode(float v) { return v <= 0.04045f ? v / 12.92f : std::pow((v + 0.055f) / 1.055f, 2.4f); }

Image tonemap_reinhard_srgb(const Image& linear) {
  Image out(linear.width, linear.height);
  for (size_t i = 0; i < linear.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const float x = std::max(0.0f, linear.pixels[i][c]);
      out.pixels[i][c] = srgb_encode(x / (1.0f + x));
    }
  return out;
}

void add_into(Image& sum, const Image& part) {
  for (size_t i = 0; i < sum.size(); ++i) sum.pixels[i] += part.pixels[i];
}

Image clip01(const Image& image) {
  Image out = image;
  for (auto& p : out.pixels) p = p.cwiseMax(0.0f).cwiseMin(1.0f);
  return out;
}

}  // namespace relight
