#include "render/render_illumination.h"

#include <tbb/parallel_for.h>

namespace relight {

IlluminationImages render_illumination(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                                       int paths_per_pixel, uint64_t seed, Progress& progress,
                                       const std::string& label) {
  const int w = gbuffer.width(), h = gbuffer.height(), spp = gbuffer.samples_per_pixel();
  const int paths = std::max(paths_per_pixel, spp);
  IlluminationImages out{Image(w, h), Image(w, h)};
  progress.begin(label, h);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      Rng rng(seed, size_t(y) * w + x);
      Vec3 surface = Vec3::Zero(), background = Vec3::Zero();
      int surface_n = 0, background_n = 0;
      for (int i = 0; i < paths; ++i) {
        const int k = i % spp;
        const GBufferSample& s = gbuffer.sample(x, y, k);
        if (s.hit) {
          surface += integrator.illumination(s.surface, rng);
          ++surface_n;
        } else if (i < spp) {  // the background needs one look per sample
          const Vec2 pos = gbuffer.sample_position(x, y, k);
          background += integrator.environment(camera.position(), camera.ray_direction(pos.x(), pos.y()));
          ++background_n;
        }
      }
      if (surface_n) out.surface.at(x, y) = surface / float(surface_n);
      if (background_n) out.background.at(x, y) = background / float(background_n);
    }
    progress.advance();
  });
  progress.end();
  return out;
}

}  // namespace relight
