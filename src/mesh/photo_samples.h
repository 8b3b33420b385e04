// What the image-based refinement reads from the photo: per pixel the
// intensity (luminance) and the input triangle the pixel shows, so that an
// edge is only read where it is itself visible.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

#include "core/image.h"
#include "mesh/line_walk.h"
#include "render/gbuffer.h"

namespace relight {

struct PhotoSamples {
  static constexpr uint32_t kNoTriangle = UINT32_MAX;
  int width = 0, height = 0;
  std::vector<float> intensity;
  std::vector<uint32_t> triangle;  // kNoTriangle where the pixel sees no geometry

  bool inside(int x, int y) const { return x >= 0 && y >= 0 && x < width && y < height; }
  float intensity_at(int x, int y) const { return intensity[size_t(y) * width + x]; }
  uint32_t triangle_at(int x, int y) const { return triangle[size_t(y) * width + x]; }
};

// The photo's luminance and the triangle seen through each pixel's centre-most
// G-buffer sample (the G-buffer must be the photo's size).
PhotoSamples photo_samples(const Image& photo, const GBuffer& gbuffer);

// Calls visit(x, y) for each pixel of the Bresenham line under the image
// segment from `from` to `to` that shows one of the `visible` triangles.
template <class Visit>
void walk_visible_pixels(const PhotoSamples& photo, const Vec2& from, const Vec2& to, std::span<const uint32_t> visible,
                         Visit&& visit) {
  // Ends on the image border (x == width after clipping) belong to the pixel inside.
  const auto pixel = [](float v, int size) { return std::clamp(int(std::floor(v)), 0, size - 1); };
  walk_line(pixel(from.x(), photo.width), pixel(from.y(), photo.height), pixel(to.x(), photo.width),
            pixel(to.y(), photo.height), [&](int x, int y) {
              if (!photo.inside(x, y)) return;
              if (std::find(visible.begin(), visible.end(), photo.triangle_at(x, y)) != visible.end()) visit(x, y);
            });
}

}  // namespace relight
