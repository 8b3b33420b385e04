#include "render/denoise.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "core/error.h"

namespace relight {

Image denoise_illumination(const Image& noisy, std::vector<float> variance, const PixelSurfaces& centre,
                           const DenoiseOptions& options) {
  const int w = noisy.width, h = noisy.height;
  static constexpr float kKernel[3] = {3.0f / 8.0f, 1.0f / 4.0f, 1.0f / 16.0f};  // B3 spline, |offset| 0, 1, 2
  Image current = noisy, next(w, h);
  std::vector<float> next_variance(variance.size());

  for (int pass = 0; pass < options.passes; ++pass) {
    if (options.progress && options.progress->cancelled()) throw Cancelled();
    const int step = 1 << pass;
    std::vector<float> lum(current.size());
    for (size_t i = 0; i < lum.size(); ++i) lum[i] = luminance(current.pixels[i]);
    tbb::parallel_for(0, h, [&](int y) {
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        if (!centre.hit[i]) {
          next.pixels[i] = current.pixels[i];
          next_variance[i] = variance[i];
          continue;
        }
        const float lum_p = lum[i];
        const float lum_scale = options.luminance_sigma * std::sqrt(std::max(variance[i], 0.0f)) + 1e-6f;
        const SurfacePoint& p = centre.surface[i];
        const float plane_scale = options.plane_sigma * p.distance;
        Vec3 sum = Vec3::Zero();
        float weight_sum = 0.0f, variance_sum = 0.0f;
        for (int dy = -2; dy <= 2; ++dy)
          for (int dx = -2; dx <= 2; ++dx) {
            const int qx = x + dx * step, qy = y + dy * step;
            if (qx < 0 || qy < 0 || qx >= w || qy >= h) continue;
            const size_t j = size_t(qy) * w + qx;
            if (!centre.hit[j]) continue;
            const SurfacePoint& q = centre.surface[j];
            const float n_dot = p.normal.dot(q.normal);
            if (n_dot <= 0.0f) continue;
            const float plane = std::abs(p.geometric_normal.dot(q.position - p.position));
            const float lum_diff = std::abs(lum[j] - lum_p);
            // n_dot^normal_power x exp(-plane) x exp(-lum_diff) as one exponential:
            // the filter's cost is these transcendentals, 25 per pixel and pass.
            const float weight =
                kKernel[std::abs(dx)] * kKernel[std::abs(dy)] *
                std::exp(options.normal_power * std::log(n_dot) - plane / plane_scale - lum_diff / lum_scale);
            sum += weight * current.pixels[j];
            weight_sum += weight;
            variance_sum += weight * weight * variance[j];
          }
        next.pixels[i] = weight_sum > 0.0f ? Vec3(sum / weight_sum) : current.pixels[i];
        next_variance[i] = weight_sum > 0.0f ? variance_sum / (weight_sum * weight_sum) : variance[i];
      }
    });
    std::swap(current, next);
    std::swap(variance, next_variance);
  }
  return current;
}

namespace {
// Rows a pass of step 2^k reaches each way is 2 x 2^k: all passes together,
// 2 (2^passes - 1).
int filter_reach(int passes) { return 2 * ((1 << passes) - 1); }
// About this many pixels to a band by default (4 M: 200 MB of surfaces and
// images; the rows beyond it cost a sixth more filtering at 24 Mpixel).
constexpr int64_t kBandPixels = int64_t(1) << 22;
}  // namespace

Image denoise_illumination(const Image& noisy, const std::vector<float>& variance, const GBuffer& gbuffer,
                           const DenoiseOptions& options) {
  const int w = noisy.width, h = noisy.height, reach = filter_reach(options.passes);
  const int band = options.band_rows > 0 ? options.band_rows : std::max(reach, int(kBandPixels / std::max(w, 1)));
  if (band >= h) return denoise_illumination(noisy, variance, PixelSurfaces::central_samples(gbuffer), options);
  Image out(w, h);
  for (int first = 0; first < h; first += band) {
    const int end = std::min(h, first + band), top = std::max(0, first - reach), bottom = std::min(h, end + reach);
    const size_t from = size_t(top) * w, to = size_t(bottom) * w;
    Image rows(w, bottom - top);
    std::copy(noisy.pixels.begin() + ptrdiff_t(from), noisy.pixels.begin() + ptrdiff_t(to), rows.pixels.begin());
    const Image filtered = denoise_illumination(
        rows, std::vector<float>(variance.begin() + ptrdiff_t(from), variance.begin() + ptrdiff_t(to)),
        PixelSurfaces::central_samples(gbuffer, top, bottom), options);
    const auto kept = filtered.pixels.begin() + ptrdiff_t(size_t(first - top) * w);
    std::copy(kept, kept + ptrdiff_t(size_t(end - first) * w), out.pixels.begin() + ptrdiff_t(size_t(first) * w));
  }
  return out;
}

}  // namespace relight
