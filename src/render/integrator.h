// Integrator: the light arriving at a diffuse surface point — direct light
// from every light (next-event estimation with shadow rays; many lights share
// them by resampling), the environment
// (importance-sampled, multiple importance sampling with the cosine lobe), and
// multi-bounce diffuse interreflection (path tracing) with a white or a given
// albedo on the surfaces light bounces off.
#pragma once

#include <optional>
#include <vector>

#include "core/sampling.h"
#include "render/ggx.h"
#include "render/ray_scene.h"
#include "scene/environment.h"
#include "scene/gloss.h"
#include "scene/light.h"

namespace relight {

// The diffuse albedo of scene surfaces that light bounces off.
class SurfaceAlbedo {
 public:
  virtual ~SurfaceAlbedo() = default;
  virtual Vec3 at(const SurfacePoint& p) const = 0;
};

// The thesis's assumption for the initial illumination: every surface white.
class WhiteAlbedo final : public SurfaceAlbedo {
 public:
  Vec3 at(const SurfacePoint&) const override { return Vec3::Ones(); }
};

// A diffuse albedo the same everywhere (the default for surfaces no photo
// shows).
class UniformAlbedo final : public SurfaceAlbedo {
 public:
  explicit UniformAlbedo(const Vec3& albedo) : albedo_(albedo) {}
  Vec3 at(const SurfacePoint&) const override { return albedo_; }

 private:
  Vec3 albedo_;
};

// The radiance scene points send out where it is known without rendering
// (a photo shows it): a path that reaches such a point ends there with it.
class KnownRadiance {
 public:
  virtual ~KnownRadiance() = default;
  // The radiance p sends back along the ray that reached it, if known.
  virtual std::optional<Vec3> at(const SurfacePoint& p) const = 0;
};

// What lights the scene in one render: the lights and the environment.
struct Lighting {
  std::vector<Light> lights;  // disabled lights are skipped
  Environment environment = Environment::constant(Vec3::Zero());

  // The lights alone, with no environment.
  Lighting lights_only() const { return {lights, Environment::constant(Vec3::Zero())}; }
};

struct IntegratorOptions {
  // Diffuse bounces after the first surface (0: direct light only). Paths
  // end by Russian roulette long before the default, a safety bound: a
  // closed room bounces its light many times, and a cut drops that light.
  int max_bounces = kMaxBounces;
  static constexpr int kMaxBounces = 64;
  int roulette_after = 2;  // Russian roulette from this bounce on
  // false: leave out the light reaching the first surface straight from the
  // lights (`direct` stays 0), for renders that add it apart (the
  // interactive engine renders each light's direct light by itself).
  bool first_surface_lights = true;
  // Up to this many lights (suns aside) each get a shadow ray at every
  // point; more (a string of bulbs) share one, resampled (from_pooled_lights).
  int max_exhaustive_lights = 16;
  // The glossy surfaces light bounces off, beside their albedo (a path
  // goes on by their lobe or by the cosine); null: every surface matte.
  const SurfaceGloss* gloss = nullptr;
};

class Integrator {
 public:
  // albedo: the albedo of surfaces reached by bounces (nullptr: white).
  // known: where given, a bounce that reaches a point of known radiance
  // ends there with it instead of going on with the albedo.
  Integrator(const RayScene& scene, const Lighting& lighting, const SurfaceAlbedo* albedo,
             IntegratorOptions options = {}, const KnownRadiance* known = nullptr);

  // The radiance a white Lambertian surface at p would reflect: the
  // irradiance at p divided by pi. One random path; average many.
  // `direct` gets the part from the lights straight to p (sharp shadows,
  // little noise), `indirect` the environment and all interreflection (smooth,
  // noisy: the part worth denoising).
  // first_bounce, where given, is the 2D sample of the first bounce's
  // direction (a pixel's paths stratify it: less noise than independent
  // ones where the light arriving varies a lot across the hemisphere).
  void illumination(const SurfacePoint& p, Rng& rng, Vec3& direct, Vec3& indirect,
                    const Vec2* first_bounce = nullptr) const {
    direct = direct_light(p, rng);
    indirect = indirect_light(p, rng, first_bounce);
  }
  // The two parts apart (rendered at different densities:
  // render_illumination.h). direct_light is 0 without first_surface_lights.
  Vec3 direct_light(const SurfacePoint& p, Rng& rng) const;
  Vec3 indirect_light(const SurfacePoint& p, Rng& rng, const Vec2* first_bounce = nullptr) const;
  Vec3 illumination(const SurfacePoint& p, Rng& rng) const {
    Vec3 d, i;
    illumination(p, rng, d, i);
    return d + i;
  }

  // indirect_light in two steps, for light after light along the same
  // paths (KeptPaths): bounce_vertices follows the path as indirect_light
  // does and keeps the vertices after its first surface, each with the
  // weight the light reaching it counts with (the environment and known
  // radiance the path meets are not kept: the paths serve lights alone).
  // Of a scene whose surfaces are all matte: a glossy vertex's highlight of
  // the lights is not kept.
  // light_at_vertex is then the lights' share at one such vertex, as
  // indirect_light adds it there. The vertices do not depend on the lights.
  struct PathVertex {
    Vec3 position, normal, geometric_normal;
    float lift;
    Vec3 throughput;
  };
  void bounce_vertices(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce,
                       std::vector<PathVertex>& out) const;
  Vec3 light_at_vertex(const PathVertex& vertex, Rng& rng) const;

  // Whether every path's light is 0: no light lit, a black environment and
  // no known radiance.
  bool is_dark() const {
    return active_lights_.empty() && pooled_lights_.empty() && lighting_.environment.is_black() && !known_;
  }

  // Environment radiance seen along a camera ray from `origin`.
  Vec3 environment(const Vec3& origin, const Vec3& dir) const;

  // The lights' light that a glossy surface at p reflects towards v (unit,
  // away from the surface) by `lobe`: each light sampled once with a shadow
  // ray (among many, one drawn by power). One estimate; average many.
  Vec3 specular_from_lights(const SurfacePoint& p, const GgxLobe& lobe, const Vec3& v, Rng& rng) const;
  const RayScene& rays() const { return scene_; }

 private:
  // Light from the lights, and one environment sample, reflected by a white surface at p.
  Vec3 from_lights(const SurfacePoint& p, Rng& rng) const;
  // The irradiance of one light sample at p where it is above p's surface
  // and unoccluded, else 0.
  Vec3 unoccluded(const SurfacePoint& p, const LightSample& s) const;
  // Many lights: kLightCandidates drawn by power, one of them kept with
  // probability proportional to its unshadowed irradiance at p (resampled
  // importance sampling, Talbot et al. 2005), one shadow ray to it: an
  // unbiased estimate of their irradiance whose cost does not grow with
  // their number.
  Vec3 from_pooled_lights(const SurfacePoint& p, Rng& rng) const;
  Vec3 from_environment(const SurfacePoint& p, const ProbeEnvironment* probe, Rng& rng) const;
  Vec3 specular_from_light(const SurfacePoint& p, const GgxLobe& lobe, const Vec3& v, const LightSampler& light,
                           Rng& rng) const;
  // One path from `start`: the environment and known radiance it meets,
  // plus lights_at(vertex, diffuse, specular, outgoing) at each vertex after
  // the first: the weights its diffuse light (albedo included; 0 where the
  // vertex's diffuse light is known) and its gloss's highlight (0 where
  // matte) count with, and the unit direction back along the path.
  template <class LightsAt>
  Vec3 follow_path(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce, const LightsAt& lights_at) const;

  const RayScene& scene_;
  const Lighting& lighting_;
  const SurfaceAlbedo* albedo_;
  IntegratorOptions options_;
  const KnownRadiance* known_;
  std::vector<LightSampler> active_lights_;  // each sampled at every point
  std::vector<LightSampler> pooled_lights_;  // resampled (from_pooled_lights)
  Distribution1D pooled_power_;              // their powers, for drawing candidates
};

}  // namespace relight
