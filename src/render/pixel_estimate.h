// A pixel's estimate as the renders make it (render_illumination.cpp,
// specular.cpp): so many estimates spread evenly over the pixel's G-buffer
// samples, their mean and its noise. Internal to src/render.
#pragma once

#include <algorithm>
#include <vector>

#include "core/sampling.h"
#include "render/gbuffer.h"

namespace relight {

// Each part draws its own random numbers at a pixel, so that the noise of
// one does not depend on how many the other drew.
constexpr uint64_t kPhotoStream = 0, kDirectStream = 1, kIndirectStream = 2, kKeptPathStream = 3, kSpecularStream = 4,
                   kSurveyStream = 5;

struct PixelEstimate {
  Vec3 mean = Vec3::Zero();
  float variance = 0.0f;  // of the mean's luminance
};

// A pixel's estimates summed: their mean, and the variance of that mean's
// luminance (which the denoiser weighs by).
class EstimateSum {
 public:
  void add(const Vec3& v) {
    sum_ += v;
    const double l = luminance(v);
    lum_sum_ += l;
    lum_sq_sum_ += l * l;
    ++n_;
  }
  PixelEstimate estimate() const {
    PixelEstimate e;
    if (n_) {
      e.mean = sum_ / float(n_);
      const double mean = lum_sum_ / n_;
      e.variance = float(std::max(0.0, lum_sq_sum_ / n_ - mean * mean) / n_);
    }
    return e;
  }

 private:
  Vec3 sum_ = Vec3::Zero();
  double lum_sum_ = 0.0, lum_sq_sum_ = 0.0;
  int n_ = 0;
};

// max(paths_per_pixel, sub-samples) estimates spread evenly over the
// pixel's sub-samples, added to a Sum over those that see geometry:
// estimate(surface, path, paths, rng) gives one (what Sum::add takes).
template <class Sum, class Estimate>
Sum sum_pixel(const GBuffer& g, int x, int y, int paths_per_pixel, Rng& rng, const Estimate& estimate) {
  const int spp = g.samples_per_pixel();
  const int paths = std::max(paths_per_pixel, spp);
  thread_local std::vector<GBufferSample> samples;  // fetched once: most are recomputed when asked for
  g.pixel_samples(x, y, samples);
  Sum sum;
  for (int i = 0; i < paths; ++i) {
    const GBufferSample s = samples[size_t(i % spp)];
    if (s.hit) sum.add(estimate(s.surface, i, paths, rng));
  }
  return sum;
}

// Their mean and its noise.
template <class Estimate>
PixelEstimate estimate_pixel(const GBuffer& g, int x, int y, int paths_per_pixel, Rng& rng, const Estimate& estimate) {
  return sum_pixel<EstimateSum>(g, x, y, paths_per_pixel, rng, estimate).estimate();
}

}  // namespace relight
