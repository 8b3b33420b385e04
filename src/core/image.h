// Image: a linear-float RGB raster, row 0 at the top, the one pixel type used
// for photos, albedo, illumination and masks inside the program.
#pragma once

#include <utility>
#include <vector>

#include "core/vec.h"

namespace relight {

struct Image {
  int width = 0;
  int height = 0;
  std::vector<Vec3> pixels;

  Image() = default;
  Image(int w, int h, const Vec3& fill = Vec3::Zero()) : width(w), height(h), pixels(size_t(w) * h, fill) {}
  Image(const Image&) = default;
  Image& operator=(const Image&) = default;
  // A moved-from image is 0 x 0: its size never promises pixels it gave
  // away. (The session renders a light's next interactive image into the
  // last one's storage when the size matches; a moved-from image that kept
  // its size sent it writing through a null pointer.)
  Image(Image&& other) noexcept
      : width(std::exchange(other.width, 0)), height(std::exchange(other.height, 0)), pixels(std::move(other.pixels)) {
    other.pixels.clear();
  }
  Image& operator=(Image&& other) noexcept {
    if (this != &other) {
      width = std::exchange(other.width, 0);
      height = std::exchange(other.height, 0);
      pixels = std::move(other.pixels);
      other.pixels.clear();
    }
    return *this;
  }

  bool empty() const { return pixels.empty(); }
  size_t size() const { return pixels.size(); }
  Vec3& at(int x, int y) { return pixels[size_t(y) * width + x]; }
  const Vec3& at(int x, int y) const { return pixels[size_t(y) * width + x]; }
};

// sum += part, pixel by pixel (the two the same size): no third image.
void add_into(Image& sum, const Image& part);

// Peak signal-to-noise ratio in dB of `test` against `reference` over the
// pixels whose weight is > 0 (weight null: all pixels), with peak 1.
double psnr(const Image& test, const Image& reference, const std::vector<float>* weight = nullptr);

// The per-channel maps used to compare HDR images the way the project's
// evaluation does: x/(1+x) tone mapping then sRGB encoding; and clipping to [0,1].
Image tonemap_reinhard_srgb(const Image& linear);
Image clip01(const Image& image);

float srgb_encode(float linear);
float srgb_decode(float encoded);

}  // namespace relight
