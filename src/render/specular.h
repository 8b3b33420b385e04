// Specular reflection: what a glossy surface (scene/gloss.h) reflects
// towards the eye on top of its diffuse part, so that
//
//   photo = albedo x illumination + specular
//
// The lobe is GGX (Walter et al. 2007) with the dielectric's Fresnel term
// and separable Smith shadowing, single scattering, as Blender's Principled
// BSDF has it in Cycles. One bounce is glossy: light reaches the surface
// from the lights (sampled, with shadow rays), the environment, or another
// surface (the lobe's reflected ray traced against the geometry), and that
// surface's light is diffuse.
#pragma once

#include <functional>

#include "core/image.h"
#include "core/progress.h"
#include "core/sampling.h"
#include "render/gbuffer.h"
#include "render/ggx.h"
#include "render/integrator.h"
#include "scene/gloss.h"

namespace relight {

// The radiance a surface point sends back along the reflected ray that met it.
using ReflectedRadiance = std::function<Vec3(const SurfacePoint& hit, Rng& rng)>;

class SpecularReflection {
 public:
  // lights: an integrator of the lighting the highlights are of (its lights
  // and environment). Holds references to all three: they must outlive it.
  SpecularReflection(const Integrator& lights, const SurfaceGloss& gloss, const ReflectedRadiance& surfaces);
  // One estimate of the radiance the gloss at p reflects towards `eye`:
  // every light sampled once (Integrator::specular_from_lights), and one
  // direction of the lobe traced — the environment where it leaves the
  // scene, `surfaces` where it meets one. 0 where p is matte.
  Vec3 radiance(const SurfacePoint& p, const Vec3& eye, Rng& rng) const;
  const SurfaceGloss& gloss() const { return gloss_; }

 private:
  const Integrator& lights_;
  const SurfaceGloss& gloss_;
  const ReflectedRadiance& surfaces_;
};

// The specular radiance of every pixel: the mean, over the pixel's samples
// that see geometry, of `paths_per_pixel` estimates spread over them (0 on
// matte samples); an image of zeros where every surface is matte.
Image render_specular(const GBuffer& gbuffer, const Camera& camera, const SpecularReflection& specular,
                      int paths_per_pixel, uint64_t seed, Progress& progress, const std::string& label = "highlights");

// Whether any pixel of the G-buffer sees a glossy surface.
bool sees_gloss(const GBuffer& gbuffer, const SurfaceGloss& gloss);

}  // namespace relight
