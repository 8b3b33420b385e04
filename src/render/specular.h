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
#include <vector>

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

// A highlight in its two parts: the lights' own (their samples through the
// lobe), and what the lobe's traced direction brings (the lit surfaces and
// the environment the gloss mirrors).
struct SpecularParts {
  Vec3 lights = Vec3::Zero(), reflected = Vec3::Zero();
};

class SpecularReflection {
 public:
  // lights: an integrator of the lighting the highlights are of (its lights
  // and environment). Holds references to all three: they must outlive it.
  SpecularReflection(const Integrator& lights, const SurfaceGloss& gloss, const ReflectedRadiance& surfaces);
  // One estimate of the radiance the gloss at p reflects towards `eye`, in
  // its parts: every light sampled once (Integrator::specular_from_lights),
  // and one direction of the lobe traced — the environment where it leaves
  // the scene, `surfaces` where it meets one. 0 where p is matte.
  SpecularParts parts(const SurfacePoint& p, const Vec3& eye, Rng& rng) const;
  // Both parts' sum.
  Vec3 radiance(const SurfacePoint& p, const Vec3& eye, Rng& rng) const {
    const SpecularParts s = parts(p, eye, rng);
    return s.lights + s.reflected;
  }
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

// The same in its two parts (SpecularReflection::parts), in one pass.
struct SpecularImages {
  Image lights, reflected;
};
SpecularImages render_specular_parts(const GBuffer& gbuffer, const Camera& camera, const SpecularReflection& specular,
                                     int paths_per_pixel, uint64_t seed, Progress& progress,
                                     const std::string& label = "highlights");

// Whether any pixel of the G-buffer sees a glossy surface.
bool sees_gloss(const GBuffer& gbuffer, const SurfaceGloss& gloss);

// The highlights of one light as the interactive frame shows them while the
// light moves: at each pixel whose one surface (PixelSurfaces) is glossy,
// the lobe's BRDF towards the light times the light's irradiance there,
// shadowed — pi x that BRDF x the pixel's direct light as a fast backend
// renders it (irradiance / pi, from the light's centre). Towards the
// light's centre, or for a soft point or an area light (as the sphere of
// its area) wider than the lobe, its representative point with the lobe's
// normalisation (Karis 2013). No ray of its own, so it follows the light at
// the frame's pace on either backend. It leaves out what the refinement
// adds: the lit surfaces and environment the lobe reflects, the pixel's
// other samples. Its far tail is taken off (GgxLobe::brdf's `tail`, a
// thousandth): most of a narrow lobe's pixels then cost half the arithmetic.
class MovingHighlights {
 public:
  MovingHighlights(const PixelSurfaces& surfaces, const SurfaceGloss& gloss, const Vec3& eye);
  // The pixels whose surface is glossy, in order: the only ones render() writes.
  const std::vector<uint32_t>& pixels() const { return pixels_; }
  bool empty() const { return pixels_.empty(); }
  // Writes the glossy pixels of `out` (the view's size; its other pixels are
  // left as they are: zero in a fresh image) for `light`, whose direct light
  // the fast backend rendered as `direct`.
  void render(const Light& light, const Image& direct, Image& out) const;

 private:
  // What a glossy pixel's highlight needs, packed: a frame reads it for
  // every glossy pixel.
  struct GlossyPixel {
    Vec3 position, normal, to_eye, mirror;  // unit: to_eye, and mirror, to_eye reflected about the normal
    GgxLobe lobe;
    GgxLobe::ViewTerms view;
  };
  std::vector<uint32_t> pixels_;
  std::vector<GlossyPixel> glossy_;  // one per pixels_
};

}  // namespace relight
