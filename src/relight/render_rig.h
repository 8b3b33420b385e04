// Relighting: the photo under a new lighting design. The new illumination
// (direct light of the rig, the scene's environment x environment_scale, and
// interreflection off the recovered albedo) multiplies the albedo (thesis
// chapter 5's modulation, done offline by path tracing). The interactive
// session (session.h) renders with the same pieces, so that it converges to
// exactly this image.
#pragma once

#include "analysis/analysed_scene.h"
#include "render/render_illumination.h"
#include "render/specular.h"

namespace relight {

struct RenderOptions {
  int paths_per_pixel = 64;
  int max_bounces = IntegratorOptions::kMaxBounces;
  // The environment and bounce light traced at every this-many-th pixel each
  // way (IlluminationOptions::indirect_stride); 0: the analysis's.
  int indirect_stride = 0;
};

// The analysis's layers of a re-lit image, at the photo's size or a view's:
// the coverage-weighted albedo, and what shows where geometry does not cover
// a pixel for environment_scale 1 — (1 - c) x the environment behind the
// pixel, or the photo itself where c = 0.
struct RelitLayers {
  Image albedo_coverage;
  Image background;
};
RelitLayers photo_layers(const Scene& scene, const Analysis& analysis);

// A rig's new environment, to light with (scale 1).
Environment rig_environment(const RigEnvironment& environment);

// `environment` turned by `degrees` about its up, counter-clockwise seen
// from above (up towards the viewer): its forward turned so, in a new
// probe (the image copied; the session keeps its sampling table). A
// constant colour is itself.
RigEnvironment turned_environment(const RigEnvironment& environment, float degrees);

// What a pixel shows of `background` (the radiance behind its background
// samples, IlluminationImages::background) where geometry does not cover it:
// (1 - c) x background, the layer that replaces the photo's.
Image seen_environment(const std::vector<float>& coverage, const Image& background);

// The re-lit pixel: c·a·illumination + environment_scale·background.
Image compose_relit(const RelitLayers& layers, const Image& illumination, float environment_scale);

// The re-lit image of `rig` from its new illumination (rendered with
// rig_lighting) on `layers` of pixels of coverage `coverage`: with a new
// environment the pixels past the geometry show it (light.background,
// already x environment_scale), else the photo's background x the scale.
Image relit_image(RelitLayers layers, const std::vector<float>& coverage, const IlluminationImages& light,
                  const Rig& rig);

// Renders new illumination the way render_rig does: the analysis's
// environment, interreflection off the recovered albedo, the analysis's seed
// and settings. Holds a reference to the analysed scene.
class NewIllumination {
 public:
  explicit NewIllumination(const AnalysedScene& analysed);

  // The environment at scale 1 (the probes or background, per the strategy).
  const Environment& environment() const { return analysed_.environment(); }
  // A rig's environment at scale 1: its new one, or the scene's.
  Environment environment(const std::optional<RigEnvironment>& environment) const;
  // The rig's lights and its environment (the new one, or the scene's) x
  // environment_scale.
  Lighting rig_lighting(const Rig& rig) const;

  // The illumination of the pixels of `gbuffer` (the photo's, or a view's
  // made with `camera`) under `lighting`. first_surface_lights false leaves
  // out the light straight from the lights (see IntegratorOptions).
  // With `kept` (keep_paths of these options), the bounce light follows
  // those paths.
  IlluminationImages render(const GBuffer& gbuffer, const Camera& camera, const Lighting& lighting,
                            const RenderOptions& options, Progress& progress, const std::string& label,
                            bool first_surface_lights = true, const KeptPaths* kept = nullptr) const;
  // The paths render() with `options` traces the bounce light along, kept
  // for light after light (KeptPaths).
  KeptPaths keep_paths(const GBuffer& gbuffer, const RenderOptions& options, Progress& progress) const;
  // The illumination options render() uses with `options`.
  IlluminationOptions illumination_options(const RenderOptions& options) const;
  // Its paths' settings: the bounces `options` allow, the scene's gloss.
  IntegratorOptions integrator_options(const RenderOptions& options) const;
  // The radiance of `lighting`'s environment behind each pixel's background
  // samples (IlluminationImages::background) alone: no path is traced.
  Image render_background(const GBuffer& gbuffer, const Camera& camera, const Lighting& lighting) const;
  // The highlights `lighting` makes on the glossy surfaces the pixels of
  // `gbuffer` see (render/specular.h), a reflected ray meeting a surface
  // taking the recovered albedo times its light; an empty image where no
  // pixel sees a glossy surface.
  Image highlights(const GBuffer& gbuffer, const Camera& camera, const Lighting& lighting, const RenderOptions& options,
                   Progress& progress) const;
  // The same in its two parts (SpecularParts); both empty where no pixel
  // sees a glossy surface.
  SpecularImages highlight_parts(const GBuffer& gbuffer, const Camera& camera, const Lighting& lighting,
                                 const RenderOptions& options, Progress& progress) const;

 private:
  // render(specular, paths_per_pixel, seed) with the highlights of
  // `lighting` as highlights() takes them.
  template <class Render>
  auto render_highlights(const Lighting& lighting, const RenderOptions& options, const Render& render) const;

  const AnalysedScene& analysed_;
};

// Adds the highlights (NewIllumination::highlights; none where empty) to a
// re-lit image, each pixel's times its coverage.
void add_highlights(Image& relit, const std::vector<float>& coverage, const Image& highlights);

// The re-lit photo. Pixels that see no geometry show the photo's background
// times the rig's environment_scale, or the rig's new environment as the
// camera sees it.
Image render_rig(const AnalysedScene& analysed, const Rig& rig, const RenderOptions& options, Progress& progress);

// A rig holding the scene's own lights and its environment unchanged.
Rig rig_from_scene(const Scene& scene);

}  // namespace relight
