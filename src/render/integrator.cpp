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
  return scene_.occluded(ray.origin, ray.dir, ray.tmax) ? Vec3::Zero() : s.irradiance;
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
      if (cos_theta > 0.0f && !scene_.occluded(ray.origin, ray.dir, ray.tmax)) {
        // Below the facet the path's bounce is not cast (it would leave
        // through the facet), so this sample is the only one that reaches d.
        const float weight = d.dot(p.geometric_normal) > 0.0f ? power_heuristic(pdf, cos_theta * kInvPi) : 1.0f;
        sum += env.radiance(probe, d) * (cos_theta * kInvPi / pdf * weight);
      }
    }
  }
  return sum;
}

Vec3 Integrator::direct_light(const SurfacePoint& p, Rng& rng) const {
  return options_.first_surface_lights ? from_lights(p, rng) : Vec3::Zero();
}

template <class LightsAt>
Vec3 Integrator::follow_path(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce,
                             const LightsAt& lights_at) const {
  const Environment& env = lighting_.environment;
  Vec3 result = Vec3::Zero();
  Vec3 throughput = Vec3::Ones();
  SurfacePoint p = start;
  for (int bounce = 0;; ++bounce) {
    const ProbeEnvironment* probe = env.uses_probes() ? env.probe_for(p.position) : nullptr;
    if (bounce > 0) result += lights_at(p, throughput);
    result += throughput.cwiseProduct(from_environment(p, probe, rng));

    // The last bounce's ray can only bring the environment (its MIS half):
    // with none, it is not cast.
    if (bounce >= options_.max_bounces && env.is_black()) break;
    // Continue the path by a cosine-weighted bounce; its estimator weight
    // (albedo x cos/pi / pdf) is just the albedo.
    const Vec2 u = bounce == 0 && first_bounce ? *first_bounce : rng.uniform2();
    const Vec3 d = to_world(sample_cosine_hemisphere(u), p.normal);
    if (d.dot(p.geometric_normal) <= 0.0f) break;
    SurfacePoint next;
    if (!scene_.intersect(scene_.offset_origin(p, d), d, next)) {
      if (!env.is_black()) {
        const float cos_pdf = p.normal.dot(d) * kInvPi;
        result += throughput.cwiseProduct(env.radiance(probe, d)) * power_heuristic(cos_pdf, env.pdf(probe, d));
      }
      break;
    }
    if (bounce >= options_.max_bounces) break;
    if (known_)
      if (const std::optional<Vec3> radiance = known_->at(next)) {
        result += throughput.cwiseProduct(*radiance);
        break;
      }
    throughput = throughput.cwiseProduct(albedo_ ? albedo_->at(next) : Vec3::Ones());
    if (bounce + 1 >= options_.roulette_after) {
      const float q = std::min(0.95f, throughput.maxCoeff());
      if (q <= 0.0f || rng.uniform() >= q) break;
      throughput /= q;
    }
    p = next;
  }
  return result;
}

Vec3 Integrator::indirect_light(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce) const {
  return follow_path(start, rng, first_bounce, [&](const SurfacePoint& p, const Vec3& throughput) -> Vec3 {
    return throughput.cwiseProduct(from_lights(p, rng));
  });
}

void Integrator::bounce_vertices(const SurfacePoint& start, Rng& rng, const Vec2* first_bounce,
                                 std::vector<PathVertex>& out) const {
  follow_path(start, rng, first_bounce, [&](const SurfacePoint& p, const Vec3& throughput) -> Vec3 {
    out.push_back({p.position, p.normal, p.geometric_normal, p.lift, throughput});
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
