#include "render/render_illumination.h"

#include <tbb/parallel_for.h>

namespace relight {

namespace {

struct PixelSums {
  Image direct, indirect;
  std::vector<float> direct_variance, indirect_variance;  // of the pixel's mean luminance
};

// Traces paths_per_pixel paths per pixel. With seen_albedo, every camera
// sample is weighted by the albedo of the surface it sees (a photo).
PixelSums trace_pixels(const GBuffer& gbuffer, const Integrator& integrator, const SurfaceAlbedo* seen_albedo,
                       int paths_per_pixel, uint64_t seed, Progress& progress, const std::string& label) {
  const int w = gbuffer.width(), h = gbuffer.height(), spp = gbuffer.samples_per_pixel();
  const int paths = std::max(paths_per_pixel, spp);
  PixelSums r{Image(w, h), Image(w, h), std::vector<float>(size_t(w) * h, 0.0f),
              std::vector<float>(size_t(w) * h, 0.0f)};
  progress.begin(label, h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      Rng rng(seed, size_t(y) * w + x);
      Vec3 direct_sum = Vec3::Zero(), indirect_sum = Vec3::Zero();
      double lum_sum = 0.0, lum_sq_sum = 0.0, direct_lum_sum = 0.0, direct_lum_sq_sum = 0.0;
      int surface_n = 0;
      // The first bounces of the pixel's paths: a randomly shifted
      // Hammersley set, spread over the hemisphere evenly.
      const Vec2 shift = rng.uniform2();
      for (int i = 0; i < paths; ++i) {
        const int k = i % spp;
        const GBufferSample& s = gbuffer.sample(x, y, k);
        if (s.hit) {
          Vec3 d, ind;
          const Vec2 first_bounce = shifted(hammersley(i, paths), shift);
          integrator.illumination(s.surface, rng, d, ind, &first_bounce);
          if (seen_albedo) {
            const Vec3 a = seen_albedo->at(s.surface);
            d = d.cwiseProduct(a);
            ind = ind.cwiseProduct(a);
          }
          direct_sum += d;
          indirect_sum += ind;
          const double l = luminance(ind), ld = luminance(d);
          lum_sum += l;
          lum_sq_sum += l * l;
          direct_lum_sum += ld;
          direct_lum_sq_sum += ld * ld;
          ++surface_n;
        }
      }
      const size_t idx = size_t(y) * w + x;
      if (surface_n) {
        r.direct.pixels[idx] = direct_sum / float(surface_n);
        r.indirect.pixels[idx] = indirect_sum / float(surface_n);
        const auto variance_of_mean = [&](double sum, double sq_sum) {
          const double mean = sum / surface_n;
          return float(std::max(0.0, sq_sum / surface_n - mean * mean) / surface_n);
        };
        r.indirect_variance[idx] = variance_of_mean(lum_sum, lum_sq_sum);
        r.direct_variance[idx] = variance_of_mean(direct_lum_sum, direct_lum_sq_sum);
      }
    }
    progress.advance();
  });
  progress.end();
  return r;
}

bool all_zero(const Image& image) {
  for (const Vec3& p : image.pixels)
    if (!p.isZero()) return false;
  return true;
}

}  // namespace

Image render_background(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator) {
  const int w = gbuffer.width(), h = gbuffer.height();
  Image out(w, h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      Vec3 sum = Vec3::Zero();
      int n = 0;
      for (int k = 0; k < gbuffer.samples_per_pixel(); ++k) {
        if (gbuffer.sample(x, y, k).hit) continue;
        const Vec2 pos = gbuffer.sample_position(x, y, k);
        sum += integrator.environment(camera.position(), camera.ray_direction(pos.x(), pos.y()));
        ++n;
      }
      if (n) out.at(x, y) = sum / float(n);
    }
  });
  return out;
}

Image IlluminationParts::total() const {
  Image sum = direct;
  for (size_t i = 0; i < sum.size(); ++i) sum.pixels[i] += indirect.pixels[i];
  return sum;
}

IlluminationParts render_illumination_parts(const GBuffer& gbuffer, const Integrator& integrator,
                                            const IlluminationOptions& options, Progress& progress,
                                            const std::string& label) {
  PixelSums r = trace_pixels(gbuffer, integrator, nullptr, options.paths_per_pixel, options.seed, progress, label);
  if (options.denoise) {
    DenoiseOptions indirect_options;
    indirect_options.progress = &progress;
    r.indirect = denoise_illumination(r.indirect, std::move(r.indirect_variance), gbuffer, indirect_options);
    // Direct light has sharp shadow edges: filter it only where its noise is
    // far above the local differences (soft shadows of area lights). A render
    // without direct light (the interactive engine renders it apart) has
    // nothing to filter.
    DenoiseOptions direct_options;
    direct_options.luminance_sigma = 1.0f;
    direct_options.progress = &progress;
    if (!all_zero(r.direct))
      r.direct = denoise_illumination(r.direct, std::move(r.direct_variance), gbuffer, direct_options);
  }
  return {std::move(r.direct), std::move(r.indirect)};
}

IlluminationImages render_illumination(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                                       const IlluminationOptions& options, Progress& progress,
                                       const std::string& label) {
  return {render_illumination_parts(gbuffer, integrator, options, progress, label).total(),
          render_background(gbuffer, camera, integrator)};
}

Image synthesize_photo(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                       const SurfaceAlbedo& albedo, int paths_per_pixel, uint64_t seed, Progress& progress) {
  const PixelSums r = trace_pixels(gbuffer, integrator, &albedo, paths_per_pixel, seed, progress, "photo");
  const Image background = render_background(gbuffer, camera, integrator);
  Image photo(gbuffer.width(), gbuffer.height());
  for (size_t i = 0; i < photo.size(); ++i) {
    const float c = gbuffer.coverage()[i];
    photo.pixels[i] = c * (r.direct.pixels[i] + r.indirect.pixels[i]) + (1.0f - c) * background.pixels[i];
  }
  return photo;
}

}  // namespace relight
