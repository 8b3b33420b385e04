#include "analysis/albedo.h"

#include <algorithm>
#include <cmath>

namespace relight {

namespace {

constexpr float kMinCoverage = 0.5f;        // below: too little geometry in the pixel to divide
constexpr float kMinRelativeLight = 0.01f;  // below this share of the median illumination: unreliable
constexpr float kMaxAlbedo = 10.0f;         // guards against division blow-ups
constexpr int kFillPasses = 256;

}  // namespace

AlbedoImages recover_albedo(const Image& photo, const std::vector<uint8_t>& clipped, const IlluminationImages& illum,
                            const GBuffer& g) {
  const int w = photo.width, h = photo.height;
  const bool any_clipped = clipped.size() == photo.size();
  AlbedoImages out;
  out.albedo = Image(w, h);
  out.albedo_coverage = Image(w, h);

  std::vector<float> lum;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      if (g.coverage(x, y) > 0.0f) lum.push_back(luminance(illum.surface.at(x, y)));
  std::nth_element(lum.begin(), lum.begin() + lum.size() / 2, lum.end());
  const float threshold = kMinRelativeLight * lum[lum.size() / 2];

  // known: 1 reliable, 0 to fill, -1 background (nothing to fill)
  std::vector<int8_t> known(size_t(w) * h, -1);
  std::vector<std::pair<size_t, Vec3>> at_least;  // the clipped pixels' lower bounds
  Vec3 sum = Vec3::Zero();
  size_t count = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float c = g.coverage(x, y);
      if (c <= 0.0f) continue;
      const Vec3& L = illum.surface.at(x, y);
      const size_t i = size_t(y) * w + x;
      known[i] = 0;
      if (c < kMinCoverage || luminance(L) <= threshold || L.minCoeff() <= 0.0f) continue;
      // photo = c a L + (1-c) B  =>  a = (photo - (1-c) B) / (c L)
      const Vec3 surface_part = (photo.at(x, y) - (1.0f - c) * illum.background.at(x, y)).cwiseMax(0.0f);
      const Vec3 a = surface_part.cwiseQuotient(c * L).cwiseMin(kMaxAlbedo);
      out.albedo.at(x, y) = a;
      // A clipped pixel's radiance is only known to be at least its value:
      // its albedo is filled, and then raised to that lower bound.
      if (any_clipped && clipped[i]) {
        at_least.emplace_back(i, a);
        continue;
      }
      known[i] = 1;
      sum += a;
      ++count;
    }
  if (count) out.mean = sum / float(count);

  // Grow the reliable albedo into the unreliable pixels of the same surface,
  // one ring of pixels per pass.
  for (int pass = 0; pass < kFillPasses; ++pass) {
    std::vector<std::pair<size_t, Vec3>> updates;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        if (known[size_t(y) * w + x] != 0) continue;
        Vec3 acc = Vec3::Zero();
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int nx = x + dx, ny = y + dy;
            if ((dx == 0 && dy == 0) || nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
            if (known[size_t(ny) * w + nx] != 1 || !g.same_surface(x, y, nx, ny)) continue;
            acc += out.albedo.at(nx, ny);
            ++n;
          }
        if (n) updates.emplace_back(size_t(y) * w + x, acc / float(n));
      }
    if (updates.empty()) break;
    for (const auto& [i, a] : updates) {
      out.albedo.pixels[i] = a;
      known[i] = 1;
    }
    out.filled += updates.size();
  }
  for (size_t i = 0; i < known.size(); ++i)
    if (known[i] == 0) {
      out.albedo.pixels[i] = out.mean;
      ++out.filled;
    }
  for (const auto& [i, bound] : at_least) out.albedo.pixels[i] = out.albedo.pixels[i].cwiseMax(bound);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.albedo_coverage.at(x, y) = out.albedo.at(x, y) * g.coverage(x, y);
  return out;
}

}  // namespace relight
