#include "render/render_illumination.h"

#include <tbb/parallel_for.h>

namespace relight {

IlluminationImages render_illumination(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                                       const IlluminationOptions& options, Progress& progress,
                                       const std::string& label) {
  const int w = gbuffer.width(), h = gbuffer.height(), spp = gbuffer.samples_per_pixel();
  const int paths = std::max(options.paths_per_pixel, spp);
  IlluminationImages out{Image(w, h), Image(w, h)};
  Image direct(w, h), indirect(w, h);
  std::vector<float> indirect_variance(size_t(w) * h, 0.0f);
  progress.begin(label, h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      Rng rng(options.seed, size_t(y) * w + x);
      Vec3 direct_sum = Vec3::Zero(), indirect_sum = Vec3::Zero(), background = Vec3::Zero();
      double lum_sum = 0.0, lum_sq_sum = 0.0;
      int surface_n = 0, background_n = 0;
      for (int i = 0; i < paths; ++i) {
        const int k = i % spp;
        const GBufferSample& s = gbuffer.sample(x, y, k);
        if (s.hit) {
          Vec3 d, ind;
          integrator.illumination(s.surface, rng, d, ind);
          direct_sum += d;
          indirect_sum += ind;
          const double l = luminance(ind);
          lum_sum += l;
          lum_sq_sum += l * l;
          ++surface_n;
        } else if (i < spp) {  // the background needs one look per sample
          const Vec2 pos = gbuffer.sample_position(x, y, k);
          background += integrator.environment(camera.position(), camera.ray_direction(pos.x(), pos.y()));
          ++background_n;
        }
      }
      const size_t idx = size_t(y) * w + x;
      if (surface_n) {
        direct.pixels[idx] = direct_sum / float(surface_n);
        indirect.pixels[idx] = indirect_sum / float(surface_n);
        const double mean = lum_sum / surface_n;
        // variance of the mean of surface_n samples
        indirect_variance[idx] = float(std::max(0.0, lum_sq_sum / surface_n - mean * mean) / surface_n);
      }
      if (background_n) out.background.pixels[idx] = background / float(background_n);
    }
    progress.advance();
  });
  progress.end();
  if (options.denoise) indirect = denoise_illumination(indirect, std::move(indirect_variance), gbuffer);
  for (size_t i = 0; i < out.surface.size(); ++i) out.surface.pixels[i] = direct.pixels[i] + indirect.pixels[i];
  return out;
}

}  // namespace relight
