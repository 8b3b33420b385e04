#include "relight/render_rig.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>

#include "render/specular.h"

namespace relight {

RelitLayers photo_layers(const Scene& scene, const Analysis& analysis) {
  RelitLayers layers{analysis.albedo.albedo_coverage, Image(scene.photo.width, scene.photo.height)};
  for (const auto& [i, albedo] : analysis.albedo.as_divided)
    layers.albedo_coverage.pixels[i] = analysis.coverage[i] * albedo;
  for (size_t i = 0; i < layers.background.size(); ++i) {
    const float c = analysis.coverage[i];
    layers.background.pixels[i] =
        c > 0.0f ? Vec3((1.0f - c) * analysis.illumination.background.pixels[i]) : scene.photo.pixels[i];
  }
  return layers;
}

Image compose_relit(const RelitLayers& layers, const Image& illumination, float environment_scale) {
  Image out(illumination.width, illumination.height);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i)
      out.pixels[i] = layers.albedo_coverage.pixels[i].cwiseProduct(illumination.pixels[i]) +
                      environment_scale * layers.background.pixels[i];
  });
  return out;
}

NewIllumination::NewIllumination(const AnalysedScene& analysed) : analysed_(analysed) {}

Environment rig_environment(const RigEnvironment& environment) {
  return environment.image ? Environment::from_probes({*environment.image}) : Environment::constant(environment.color);
}

RigEnvironment turned_environment(const RigEnvironment& environment, float degrees) {
  if (!environment.image) return environment;
  auto turned = std::make_shared<Probe>(*environment.image);
  const float t = degrees * kPi / 180.0f;
  const Vec3 up = turned->up.normalized(), forward = turned->forward;
  // Rodrigues' rotation of forward about up.
  turned->forward =
      std::cos(t) * forward + std::sin(t) * up.cross(forward) + (1.0f - std::cos(t)) * up.dot(forward) * up;
  return RigEnvironment{environment.color, std::move(turned)};
}

Image seen_environment(const std::vector<float>& coverage, const Image& background) {
  Image out(background.width, background.height);
  for (size_t i = 0; i < out.size(); ++i) out.pixels[i] = (1.0f - coverage[i]) * background.pixels[i];
  return out;
}

Image relit_image(RelitLayers layers, const std::vector<float>& coverage, const IlluminationImages& light,
                  const Rig& rig) {
  if (!rig.environment) return compose_relit(layers, light.surface, rig.environment_scale);
  layers.background = seen_environment(coverage, light.background);
  return compose_relit(layers, light.surface, 1.0f);
}

Environment NewIllumination::environment(const std::optional<RigEnvironment>& environment) const {
  return environment ? rig_environment(*environment) : analysed_.environment();
}

Lighting NewIllumination::rig_lighting(const Rig& rig) const {
  Lighting lighting;
  lighting.lights = rig.lights;
  lighting.environment = environment(rig.environment);
  lighting.environment.set_scale(rig.environment_scale);
  return lighting;
}

IlluminationImages NewIllumination::render(const GBuffer& gbuffer, const Camera& camera, const Lighting& lighting,
                                           const RenderOptions& options, Progress& progress, const std::string& label,
                                           bool first_surface_lights, const KeptPaths* kept) const {
  IntegratorOptions paths = integrator_options(options);
  paths.first_surface_lights = first_surface_lights;
  const Integrator integrator(analysed_.rays(), lighting, &analysed_.bounce_albedo(), paths);
  return render_illumination(gbuffer, camera, integrator, illumination_options(options), progress, label, nullptr,
                             kept);
}

KeptPaths NewIllumination::keep_paths(const GBuffer& gbuffer, const RenderOptions& options, Progress& progress) const {
  const Lighting none;
  const Integrator paths(analysed_.rays(), none, &analysed_.bounce_albedo(), integrator_options(options));
  return KeptPaths(gbuffer, paths, illumination_options(options), progress);
}

IntegratorOptions NewIllumination::integrator_options(const RenderOptions& options) const {
  IntegratorOptions paths;
  paths.max_bounces = options.max_bounces;
  paths.gloss = &analysed_.scene().gloss;
  return paths;
}

IlluminationOptions NewIllumination::illumination_options(const RenderOptions& options) const {
  // The analysis's seed: the noise of the new illumination then follows that
  // of the analysis, and an unchanged rig gives back the photo.
  IlluminationOptions illumination = relight::illumination_options(analysed_.analysis().options);
  illumination.paths_per_pixel = options.paths_per_pixel;
  if (options.indirect_stride > 0) illumination.indirect_stride = options.indirect_stride;
  return illumination;
}

Image NewIllumination::render_background(const GBuffer& gbuffer, const Camera& camera,
                                         const Lighting& lighting) const {
  return relight::render_background(gbuffer, camera,
                                    Integrator(analysed_.rays(), lighting, &analysed_.bounce_albedo()));
}

template <class Render>
auto NewIllumination::render_highlights(const Lighting& lighting, const RenderOptions& options,
                                        const Render& render) const {
  const Integrator integrator(analysed_.rays(), lighting, &analysed_.bounce_albedo(), integrator_options(options));
  const ReflectedRadiance surfaces = [&](const SurfacePoint& hit, Rng& rng) -> Vec3 {
    return analysed_.bounce_albedo().at(hit).cwiseProduct(integrator.illumination(hit, rng));
  };
  const IlluminationOptions settings = illumination_options(options);
  return render(SpecularReflection(integrator, analysed_.scene().gloss, surfaces), settings.paths_per_pixel,
                settings.seed);
}

Image NewIllumination::highlights(const GBuffer& gbuffer, const Camera& camera, const Lighting& lighting,
                                  const RenderOptions& options, Progress& progress) const {
  if (!sees_gloss(gbuffer, analysed_.scene().gloss)) return Image();
  return render_highlights(lighting, options, [&](const SpecularReflection& specular, int paths, uint64_t seed) {
    return render_specular(gbuffer, camera, specular, paths, seed, progress);
  });
}

SpecularImages NewIllumination::highlight_parts(const GBuffer& gbuffer, const Camera& camera, const Lighting& lighting,
                                                const RenderOptions& options, Progress& progress) const {
  if (!sees_gloss(gbuffer, analysed_.scene().gloss)) return {};
  return render_highlights(lighting, options, [&](const SpecularReflection& specular, int paths, uint64_t seed) {
    return render_specular_parts(gbuffer, camera, specular, paths, seed, progress);
  });
}

void add_highlights(Image& relit, const std::vector<float>& coverage, const Image& highlights) {
  for (size_t i = 0; i < highlights.size(); ++i) relit.pixels[i] += coverage[i] * highlights.pixels[i];
}

Image render_rig(const AnalysedScene& analysed, const Rig& rig, const RenderOptions& options, Progress& progress) {
  const NewIllumination renderer(analysed);
  const Lighting lighting = renderer.rig_lighting(rig);
  const GBuffer& gbuffer = analysed.gbuffer();
  const IlluminationImages light =
      renderer.render(gbuffer, analysed.scene().camera, lighting, options, progress, "new illumination");
  Image relit =
      relit_image(photo_layers(analysed.scene(), analysed.analysis()), analysed.analysis().coverage, light, rig);
  add_highlights(relit, analysed.analysis().coverage,
                 renderer.highlights(gbuffer, analysed.scene().camera, lighting, options, progress));
  return relit;
}

Rig rig_from_scene(const Scene& scene) {
  Rig rig;
  rig.environment_scale = 1.0f;
  rig.lights = scene.lights;
  return rig;
}

}  // namespace relight
