#include "render/integrator.h"

#include <algorithm>
#include <cmath>

namespace relight {

Integrator::Integrator(const RayScene& scene, const Lighting& lighting, const SurfaceAlbedo* albedo,
                       IntegratorOptions options, const KnownRadiance* known)
    : scene_(scene), lighting_(lighting), albedo_(albedo), options_(options), known_(known) {
  std::vector<const Light*> positioned;
  for (const auto& l : lighting_.lights) {
    if (!l.enabled || l.emission().isZero()) continue;
    if (l.type == LightType::directional)
      active_lights_.emplace_back(l);  // a sun lights everything alike: no point choosing
    else
      positioned.push_back(&l);
  }
  if (int(positioned.size()) <= options_.max_exhaustive_lights) {
    for (const Light* l : positioned) active_lights_.emplace_back(*l);
    return;
  }
  std::vector<float> power;
  for (const Light* l : positioned) {
    pooled_lights_.emplace_back(*l);
    power.push_back(luminance(l->emission()));
  }
  pooled_power_ = Distribution1D(std::move(power));
}

Vec3 Integrator::environment(const Vec3& origin, const Vec3& dir) const {
  const Environment& env = lighting_.environment;
  return env.radiance(env.probe_for(origin), dir);
}

Vec3 Integrator::unoccluded(const SurfacePoint& p, const LightSample& s) const {
  if (s.irradiance.isZero()) return Vec3::Zero();
  const ShadowRay ray = scene_.shadow_ray(p, s.direction, s.distance);
  return scene_.occluded(ray) ? Vec3::Zero() : s.irradiance;
}

Vec3 Integrator::from_lights(const SurfacePoint& p, Rng& rng) const {
  Vec3 sum = Vec3::Zero();
  for (const LightSampler& light : active_lights_)
    sum += unoccluded(p, light.sample(p.position, p.normal, rng.uniform2()));
  if (!pooled_lights_.empty()) sum += from_pooled_lights(p, rng);
  return sum * kInvPi;
}

Vec3 Integrator::from_pooled_lights(const SurfacePoint& p, Rng& rng) const {
  // kPicks lights a point, each resampled from kCandidates: four shadow rays
  // average the bulbs' shadows four times as well as one (6 dB less noise
  // on the example room), and cost less than the 16 lights that get a ray
  // each below the pool.
  constexpr int kPicks = 4, kCandidates = 8;
  const float lights = float(pooled_power_.size());
  Vec3 sum = Vec3::Zero();
  for (int pick = 0; pick < kPicks; ++pick) {
    float total_weight = 0.0f, kept_target = 0.0f;
    LightSample kept{};
    for (int k = 0; k < kCandidates; ++k) {
      float offset, density;
      const int i = pooled_power_.sample(rng.uniform(), offset, density);
      const LightSample s = pooled_lights_[size_t(i)].sample(p.position, p.normal, rng.uniform2());
      if (s.irradiance.isZero()) continue;
      const float target = luminance(s.irradiance);
      const float weight = target / (density / lights);  // target / the probability of drawing light i
      total_weight += weight;
      if (rng.uniform() * total_weight < weight) kept = s, kept_target = target;
    }
    if (kept_target > 0.0f) sum += unoccluded(p, kept) * (total_weight / (float(kCandidates) * kept_target));
  }
  return sum / float(kPicks);
}

Vec3 Integrator::from_environment(const SurfacePoint& p, const ProbeEnvironment* probe, Rng& rng) const {
  Vec3 sum = Vec3::Zero();
  const Environment& env = lighting_.environment;
  if (!env.is_black()) {
    Vec3 d;
    float pdf;
    const Vec2 u = rng.uniform2();
    if (env.sample(probe, u, d, pdf)) {
      const float cos_theta = p.normal.dot(d);
      const ShadowRay ray = scene_.shadow_ray(p, d, std::numeric_limits<float>::infinity());
      if (cos_theta > 0.0f && !scene_.occluded(ray)) {
        // Below the facet the path's bounce is not cast (it would leave
        // through the facet), so this sample is the only one that reaches d.
        const float weight = d.dot(p.geometric_normal) > 0.0f ? power_heuristic(pdf, cos_theta * kInvPi) : 1.0f;
        sum += env.radiance(probe, d) * (cos_theta * kInvPi / pdf * weight);
      }
    }
  }
  return sum;
}

Vec3 Integrator::specular_from_light(const SurfacePoint& p, const GgxLobe& lobe, const Vec3& v,
                                     const LightSampler& light, Rng& rng) const {
  const LightSample s = light.sample(p.position, p.normal, rng.uniform2());
  const float f = s.irradiance.isZero() ? 0.0f : lobe.brdf(p.normal, s.direction, v);
  return f > 0.0f ? Vec3(f * unoccluded(p, s)) : Vec3::Zero();
}

Vec3 Integrator::specular_from_lights(const SurfacePoint& p, const GgxLobe& lobe, const Vec3& v, Rng& rng) const {
  Vec3 sum = Vec3::Zero();
  for (const LightSampler& light : active_lights_) sum += specular_from_light(p, lobe, v, light, rng);
  if (!pooled_lights_.empty()) {
    float offset, density;
    const int i = pooled_power_.sample(rng.uniform(), offset, density);
    const float probability = density / float(pooled_power_.size());
    if (probability > 0.0f) sum += specular_from_light(p, lobe, v, pooled_lights_[size_t(i)], rng) / probability;
  }
  return sum;
}

Vec3 Integrator::direct_light(const SurfacePoint& p, Rng& rng) const {
  return options_.first_surface_lights ? from_lights(p, rng) : Vec3::Zero();
}

// A path at a glossy surface goes on by its lobe this often, by the cosine
// otherwise (unless the surface's diffuse light is known: then always by
// the lobe).
constexpr float kByLobe = 0.25f;

template <class LightsAt>
Vec3 Integrator::follow_path(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce,
                             const LightsAt& lights_at) const {
  const Environment& env = lighting_.environment;
  Vec3 result = Vec3::Zero();
  // What the light p sends back along the path counts with, and p's albedo
  // (the start's white: its own highlights are rendered apart, render/specular.h).
  Vec3 weight = Vec3::Ones(), albedo = Vec3::Ones();
  const Gloss* gloss = nullptr;
  bool known_diffuse = false;  // p's diffuse light is known: only its gloss's goes on
  Vec3 outgoing = Vec3::Zero();
  SurfacePoint p = start;
  for (int bounce = 0;; ++bounce) {
    const ProbeEnvironment* probe = env.uses_probes() ? env.probe_for(p.position) : nullptr;
    const Vec3 diffuse = known_diffuse ? Vec3::Zero() : Vec3(weight.cwiseProduct(albedo));
    if (bounce > 0) result += lights_at(p, diffuse, gloss ? weight : Vec3::Zero(), outgoing);
    if (!known_diffuse) result += diffuse.cwiseProduct(from_environment(p, probe, rng));

    // The last bounce's ray can only bring the environment (its MIS half):
    // with none, it is not cast.
    if (bounce >= options_.max_bounces && env.is_black()) break;
    // Continue the path by the gloss's lobe, or by a cosine-weighted bounce
    // (its estimator weight, albedo x cos/pi / pdf, is just the albedo).
    const float by_lobe_chance = !gloss ? 0.0f : known_diffuse ? 1.0f : kByLobe;
    const bool by_lobe = by_lobe_chance >= 1.0f || (by_lobe_chance > 0.0f && rng.uniform() < by_lobe_chance);
    Vec3 d, next_weight;
    if (by_lobe) {
      float lobe_weight;
      if (!GgxLobe(*gloss).sample(p.normal, outgoing, rng.uniform2(), d, lobe_weight)) break;
      next_weight = weight * (lobe_weight / by_lobe_chance);
    } else {
      const Vec2 u = bounce == 0 && first_bounce ? *first_bounce : rng.uniform2();
      d = to_world(sample_cosine_hemisphere(u), p.normal);
      next_weight = diffuse / (1.0f - by_lobe_chance);
    }
    if (d.dot(p.geometric_normal) <= 0.0f) break;
    SurfacePoint next;
    // It leaves as a shadow ray does, passing over the smooth surface it leaves.
    if (!scene_.intersect(scene_.shadow_ray(p, d, std::numeric_limits<float>::infinity()), next)) {
      if (!env.is_black()) {
        // The lobe's ray has no environment sample to share the direction with.
        const float mis = by_lobe ? 1.0f : power_heuristic(p.normal.dot(d) * kInvPi, env.pdf(probe, d));
        result += next_weight.cwiseProduct(env.radiance(probe, d)) * mis;
      }
      break;
    }
    if (bounce >= options_.max_bounces) break;
    weight = next_weight;
    outgoing = -d;
    gloss = options_.gloss ? options_.gloss->at(next.prim) : nullptr;
    known_diffuse = false;
    if (known_)
      if (const std::optional<Vec3> radiance = known_->at(next)) {
        result += weight.cwiseProduct(*radiance);
        if (!gloss) break;
        known_diffuse = true;  // what the photo shows of a glossy surface is its diffuse light: its gloss goes on
      }
    albedo = known_diffuse ? Vec3::Zero() : albedo_ ? albedo_->at(next) : Vec3::Ones();
    if (bounce + 1 >= options_.roulette_after) {
      // A gloss reflects a few percent (more at grazing angles).
      const float reflects = weight.cwiseProduct(albedo).maxCoeff() + (gloss ? 0.1f * weight.maxCoeff() : 0.0f);
      const float q = std::min(0.95f, reflects);
      if (q <= 0.0f || rng.uniform() >= q) break;
      weight /= q;
    }
    p = next;
  }
  return result;
}

Vec3 Integrator::indirect_light(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce) const {
  return follow_path(
      start, rng, first_bounce,
      [&](const SurfacePoint& p, const Vec3& diffuse, const Vec3& specular, const Vec3& outgoing) {
        Vec3 light = diffuse.isZero() ? Vec3::Zero() : Vec3(diffuse.cwiseProduct(from_lights(p, rng)));
        if (!specular.isZero())
          light += specular.cwiseProduct(specular_from_lights(p, GgxLobe(*options_.gloss->at(p.prim)), outgoing, rng));
        return light;
      });
}

void Integrator::bounce_vertices(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce,
                                 std::vector<PathVertex>& out) const {
  follow_path(start, rng, first_bounce, [&](const SurfacePoint& p, const Vec3& diffuse, const Vec3&, const Vec3&) {
    out.push_back({p.position, p.normal, p.geometric_normal, p.lift, diffuse});
    return Vec3::Zero();
  });
}

Vec3 Integrator::light_at_vertex(const PathVertex& v, Rng& rng) const {
  SurfacePoint p;
  p.position = v.position;
  p.normal = v.normal;
  p.geometric_normal = v.geometric_normal;
  p.lift = v.lift;
  return v.throughput.cwiseProduct(from_lights(p, rng));
}

}  // namespace relight
