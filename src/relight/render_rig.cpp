#include "relight/render_rig.h"

#include "analysis/surface_albedo.h"

namespace relight {

Image render_rig(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const Analysis& analysis,
                 const Rig& rig, const RenderOptions& options, Progress& progress) {
  Lighting lighting;
  lighting.lights = rig.lights;
  lighting.environment = strategy_environment(scene, rays, analysis.options.strategy);
  lighting.environment.set_scale(rig.environment_scale);

  const PhotoAlbedo bounce_albedo(scene.camera, gbuffer, analysis.albedo.albedo, analysis.albedo.mean);
  IntegratorOptions integrator_options;
  integrator_options.max_bounces = options.max_bounces;
  const Integrator integrator(rays, lighting, &bounce_albedo, integrator_options);
  // The analysis's seed: the noise of the new illumination then follows that
  // of the analysis, and an unchanged rig gives back the photo.
  IlluminationOptions illumination = illumination_options(analysis.options);
  illumination.paths_per_pixel = options.paths_per_pixel;
  const IlluminationImages light =
      render_illumination(gbuffer, scene.camera, integrator, illumination, progress, "new illumination");

  Image out(scene.photo.width, scene.photo.height);
  for (size_t i = 0; i < out.size(); ++i) {
    const float c = analysis.coverage[i];
    const Vec3 background = c > 0.0f ? Vec3((1.0f - c) * analysis.illumination.background.pixels[i])
                                     : scene.photo.pixels[i];
    out.pixels[i] = analysis.albedo.albedo_coverage.pixels[i].cwiseProduct(light.surface.pixels[i]) +
                    rig.environment_scale * background;
  }
  return out;
}

Rig rig_from_scene(const Scene& scene) {
  Rig rig;
  rig.environment_scale = 1.0f;
  rig.lights = scene.lights;
  return rig;
}

}  // namespace relight
