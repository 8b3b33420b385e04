#include "scene/light.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/sampling.h"

namespace relight {

const char* to_string(LightType type) {
  switch (type) {
    case LightType::point: return "point";
    case LightType::spot: return "spot";
    case LightType::area: return "area";
    case LightType::directional: return "directional";
  }
  return "?";
}

float spot_factor(const Light& light, float c) {
  const float c0 = std::cos(radians(light.spot_angle_deg) * 0.5f);
  if (c <= c0) return 0.0f;
  float s = 1.0f;
  if (light.blend > 0.0f) {
    const float t = std::clamp((c - c0) / ((1.0f - c0) * light.blend), 0.0f, 1.0f);
    s = t * t * (3.0f - 2.0f * t);
  }
  return c * s;
}

namespace {

// Point and spot lights: intensity I = power/(4 pi) (times the spot factor),
// from a point or, with a radius, from a disc of radiance power/(4 pi^2 r^2)
// facing the surface point (FORMAT.md).
LightSample sample_point_like(const Light& light, const Vec3& p, const Vec3& n, const Vec2& u) {
  LightSample s{};
  const Vec3 to_light_center = light.position - p;
  const float d2_center = to_light_center.squaredNorm();
  const Vec3 axis = to_light_center.normalized();  // disc normal faces p
  float cone = 1.0f;
  if (light.type == LightType::spot) cone = spot_factor(light, (-axis).dot(light.direction.normalized()));
  Vec3 target = light.position;
  if (light.radius > 0.0f) {
    const Vec2 d = sample_concentric_disc(u) * light.radius;
    Vec3 t, b;
    orthonormal_basis(axis, t, b);
    target += d.x() * t + d.y() * b;
  }
  const Vec3 to_light = target - p;
  s.distance = to_light.norm();
  s.direction = to_light / s.distance;
  const float cos_surface = n.dot(s.direction);
  if (cos_surface <= 0.0f || cone <= 0.0f || d2_center <= 0.0f) {
    s.irradiance = Vec3::Zero();
    return s;
  }
  const Vec3 emission = light.emission();
  if (light.radius <= 0.0f) {
    s.irradiance = emission * (cone * cos_surface / (4.0f * kPi * s.distance * s.distance));
  } else {
    // L_e cos_s cos_l A / dist^2 with L_e = P/(4 pi^2 r^2), A = pi r^2.
    const float cos_light = std::max(0.0f, axis.dot(s.direction));
    s.irradiance = emission * (cone * cos_surface * cos_light / (4.0f * kPi * s.distance * s.distance));
  }
  return s;
}

// One-sided rectangle of radiance power/(4 w h), sampled uniformly by area.
LightSample sample_area(const Light& light, const Vec3& p, const Vec3& n, const Vec2& u) {
  LightSample s{};
  const Vec3 normal = light.direction.normalized();
  const Vec3 side_w = normal.cross(light.up).normalized();  // the w side
  const Vec3 side_h = side_w.cross(normal);                 // the h side, along `up`
  const Vec3 q = light.position + (u.x() - 0.5f) * light.size.x() * side_w + (u.y() - 0.5f) * light.size.y() * side_h;
  const Vec3 to_light = q - p;
  s.distance = to_light.norm();
  s.direction = to_light / s.distance;
  const float cos_surface = n.dot(s.direction);
  const float cos_light = -normal.dot(s.direction);
  if (cos_surface <= 0.0f || cos_light <= 0.0f) {
    s.irradiance = Vec3::Zero();
    return s;
  }
  const float area = light.size.x() * light.size.y();
  const Vec3 radiance = light.emission() / (4.0f * area);
  s.irradiance = radiance * (cos_surface * cos_light * area / (s.distance * s.distance));
  return s;
}

// Sun: irradiance on a facing surface; a disc of angular diameter angle_deg
// sampled uniformly in its cone.
LightSample sample_directional(const Light& light, const Vec3& n, const Vec2& u) {
  LightSample s{};
  const Vec3 to_sun = -light.direction.normalized();
  s.direction = to_sun;
  if (light.angle_deg > 0.0f) {
    const float cos_max = std::cos(radians(light.angle_deg) * 0.5f);
    s.direction = to_world(sample_uniform_cone(u, cos_max), to_sun);
  }
  s.distance = std::numeric_limits<float>::infinity();
  s.irradiance = light.emission() * std::max(0.0f, n.dot(s.direction));
  return s;
}

}  // namespace

LightSample sample_light(const Light& light, const Vec3& p, const Vec3& n, const Vec2& u) {
  switch (light.type) {
    case LightType::point:
    case LightType::spot: return sample_point_like(light, p, n, u);
    case LightType::area: return sample_area(light, p, n, u);
    case LightType::directional: return sample_directional(light, n, u);
  }
  return {};
}

}  // namespace relight
