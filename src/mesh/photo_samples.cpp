#include "mesh/photo_samples.h"

namespace relight {

PhotoSamples photo_samples(const Image& photo, const GBuffer& gbuffer) {
  PhotoSamples s;
  s.width = photo.width;
  s.height = photo.height;
  s.intensity.resize(photo.size());
  s.triangle.resize(photo.size());
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const size_t i = size_t(y) * s.width + x;
      s.intensity[i] = luminance(photo.pixels[i]);
      const GBufferSample g = gbuffer.central(x, y);
      s.triangle[i] = g.hit ? g.surface.prim : PhotoSamples::kNoTriangle;
    }
  return s;
}

}  // namespace relight
