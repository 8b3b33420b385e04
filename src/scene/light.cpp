#include "scene/light.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "core/sampling.h"

namespace relight {

bool same_geometry(const Light& a, const Light& b) {
  return a.type == b.type && a.position == b.position && a.direction == b.direction && a.up == b.up &&
         a.radius == b.radius && a.spot_angle_deg == b.spot_angle_deg && a.blend == b.blend && a.size == b.size &&
         a.angle_deg == b.angle_deg;
}

const char* to_string(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::constant:
      return "constant";
    case Interpolation::linear:
      return "linear";
    case Interpolation::smooth:
      return "smooth";
  }
  return "smooth";
}

const char* to_string(LightType type) {
  switch (type) {
    case LightType::point: return "point";
    case LightType::spot: return "spot";
    case LightType::area: return "area";
    case LightType::directional: return "directional";
  }
  return "?";
}

namespace {

// FORMAT.md's spot cone factor c*s, with c0 = cos(spot_angle/2).
float spot_cone(float c0, float blend, float c) {
  if (c <= c0) return 0.0f;
  float s = 1.0f;
  if (blend > 0.0f) {
    const float t = std::clamp((c - c0) / ((1.0f - c0) * blend), 0.0f, 1.0f);
    s = t * t * (3.0f - 2.0f * t);
  }
  return c * s;
}

float half_angle_cosine(float full_angle_deg) { return std::cos(radians(full_angle_deg) * 0.5f); }

}  // namespace

float spot_factor(const Light& light, float c) {
  return spot_cone(half_angle_cosine(light.spot_angle_deg), light.blend, c);
}

AreaLightSides area_light_sides(const Light& light) {
  const Vec3 axis = light.direction.normalized();
  const Vec3 w = axis.cross(light.up).normalized();
  return {w, w.cross(axis)};
}

namespace {

// The solid angle of triangle abc (vectors from the viewpoint), Van
// Oosterom & Strackee (1983): tan(omega / 2) = |a . (b x c)| /
// (|a||b||c| + (a . b)|c| + (a . c)|b| + (b . c)|a|).
float triangle_solid_angle(const Vec3& a, const Vec3& b, const Vec3& c) {
  const float la = a.norm(), lb = b.norm(), lc = c.norm();
  const float numerator = std::abs(a.dot(b.cross(c)));
  const float denominator = la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la;
  return 2.0f * std::atan2(numerator, denominator);
}

// The corners of a rectangle, in order round it: centre +- half_w +- half_h.
std::array<Vec3, 4> rectangle_corners(const Vec3& centre, const Vec3& half_w, const Vec3& half_h) {
  return {centre - half_w - half_h, centre + half_w - half_h, centre + half_w + half_h, centre - half_w + half_h};
}

// Lambert (1760): a convex polygon of unit radiance, corners v_i seen from a
// point with unit normal n, wholly above its horizon, gives the irradiance
// 1/2 |sum_i theta_i n . (v_i x v_i+1) / |v_i x v_i+1||, theta_i the angle
// between v_i and v_i+1 (Arvo 1995, "Applications of irradiance tensors").
// The part of the rectangle below the horizon is cut off first
// (Sutherland-Hodgman: a plane cuts a quadrilateral into at most five
// corners).
float rectangle_irradiance(const std::array<Vec3, 4>& rectangle, const Vec3& n) {
  std::array<Vec3, 5> corners;
  size_t count = 0;
  for (size_t i = 0; i < rectangle.size(); ++i) {
    const Vec3& a = rectangle[i];
    const Vec3& b = rectangle[(i + 1) % rectangle.size()];
    const float ha = n.dot(a), hb = n.dot(b);
    if (ha >= 0.0f) corners[count++] = a;
    if ((ha >= 0.0f) != (hb >= 0.0f)) corners[count++] = a + (b - a) * (ha / (ha - hb));
  }
  double sum = 0.0;
  for (size_t i = 0; i < count; ++i) {
    const Vec3 a = corners[i].normalized(), b = corners[(i + 1) % count].normalized();
    const Vec3 normal = a.cross(b);
    const float sine = normal.norm();
    if (!(sine > 0.0f)) continue;  // a corner at the point, or an edge seen end on
    sum += std::atan2(sine, a.dot(b)) * double(n.dot(normal) / sine);
  }
  return float(0.5 * std::abs(sum));
}

}  // namespace

float area_light_solid_angle(const Light& light, const Vec3& from) {
  const AreaLightSides sides = area_light_sides(light);
  const auto [a, b, c, d] =
      rectangle_corners(light.position - from, 0.5f * light.size.x() * sides.w, 0.5f * light.size.y() * sides.h);
  return triangle_solid_angle(a, b, c) + triangle_solid_angle(a, c, d);
}

LightSampler::LightSampler(const Light& light) : light_(light), emission_(light.emission()) {
  switch (light.type) {
    case LightType::point: break;
    case LightType::spot:
      axis_ = light.direction.normalized();
      cos_outer_ = half_angle_cosine(light.spot_angle_deg);
      break;
    case LightType::area: {
      axis_ = light.direction.normalized();
      const AreaLightSides sides = area_light_sides(light);
      side_w_ = sides.w;
      side_h_ = sides.h;
      area_intensity_ = emission_ * 0.25f;  // radiance emission / (4 w h) times the area w h
      break;
    }
    case LightType::directional:
      axis_ = -light.direction.normalized();
      cos_outer_ = half_angle_cosine(light.angle_deg);
      break;
  }
}

bool LightSampler::needs_random() const {
  switch (light_.type) {
    case LightType::point:
    case LightType::spot: return light_.radius > 0.0f;
    case LightType::area: return true;
    case LightType::directional: return light_.angle_deg > 0.0f;
  }
  return true;
}

LightSample LightSampler::sample(const Vec3& p, const Vec3& n, const Vec2& u) const {
  switch (light_.type) {
    case LightType::point:
    case LightType::spot:
      return sample_point_like(p, n, &u);
    case LightType::area: return sample_area(p, n, u);
    case LightType::directional:
      return sample_directional(n, &u);
  }
  return {};
}

LightSample LightSampler::unshadowed_from_centre(const Vec3& p, const Vec3& n) const {
  switch (light_.type) {
    case LightType::point:
    case LightType::spot:
      return sample_point_like(p, n, nullptr);
    case LightType::area:
      return sample_area(p, n, Vec2(0.5f, 0.5f));
    case LightType::directional:
      return sample_directional(n, nullptr);
  }
  return {};
}

Vec3 LightSampler::direction_to_centre(const Vec3& p) const {
  if (light_.type == LightType::directional) return axis_;
  const Vec3 to_centre = light_.position - p;
  const float d2 = to_centre.squaredNorm();
  return d2 > 0.0f ? Vec3(to_centre / std::sqrt(d2)) : Vec3::UnitZ();
}

// Point and spot lights: intensity I = power/(4 pi) (times the spot factor),
// from a point or, with a radius, from a disc of radiance power/(4 pi^2 r^2)
// facing the surface point (FORMAT.md). No u: the disc's centre.
LightSample LightSampler::sample_point_like(const Vec3& p, const Vec3& n, const Vec2* u) const {
  const Light& light = light_;
  LightSample s{};
  const Vec3 to_light_center = light.position - p;
  const float d2_center = to_light_center.squaredNorm();
  if (!(d2_center > 0.0f)) {  // at the light's centre: no direction, no light
    s.direction = Vec3::UnitZ();
    s.distance = 0.0f;
    s.irradiance = Vec3::Zero();
    return s;
  }
  // One square root and one division for the centre (two with a disc):
  // they were most of the interactive engine's time per pixel.
  const float inverse_center = 1.0f / std::sqrt(d2_center);
  const Vec3 axis = to_light_center * inverse_center;  // disc normal faces p
  float cone = 1.0f;
  if (light.type == LightType::spot) cone = spot_cone(cos_outer_, light.blend, (-axis).dot(axis_));
  float inverse_distance = inverse_center;
  const bool on_disc = u && light.radius > 0.0f;
  if (on_disc) {
    const Vec2 d = sample_concentric_disc(*u) * light.radius;
    Vec3 t, b;
    orthonormal_basis(axis, t, b);
    const Vec3 to_light = light.position + d.x() * t + d.y() * b - p;
    const float d2 = to_light.squaredNorm();
    inverse_distance = 1.0f / std::sqrt(d2);
    s.distance = d2 * inverse_distance;
    s.direction = to_light * inverse_distance;
  } else {  // the centre: its direction and distance are known (the interactive engine's hot path)
    s.distance = d2_center * inverse_center;
    s.direction = axis;
  }
  const float cos_surface = n.dot(s.direction);
  if (cos_surface <= 0.0f || cone <= 0.0f) {
    s.irradiance = Vec3::Zero();
    return s;
  }
  // With a radius: L_e cos_s cos_l A / dist^2 with L_e = P/(4 pi^2 r^2), A = pi r^2.
  constexpr float kInverse4Pi = 1.0f / (4.0f * kPi);
  const float cos_light = on_disc ? std::max(0.0f, axis.dot(s.direction)) : 1.0f;
  s.irradiance = emission_ * (cone * cos_surface * cos_light * inverse_distance * inverse_distance * kInverse4Pi);
  return s;
}

Vec3 LightSampler::unshadowed_irradiance(const Vec3& p, const Vec3& n) const {
  const Light& light = light_;
  if (axis_.dot(p - light.position) <= 0.0f) return Vec3::Zero();              // behind the emitting side
  const Vec3 radiance = emission_ / (4.0f * light.size.x() * light.size.y());  // FORMAT.md
  return radiance * rectangle_irradiance(rectangle_corners(light.position - p, 0.5f * light.size.x() * side_w_,
                                                           0.5f * light.size.y() * side_h_),
                                         n);
}

// One-sided rectangle of radiance power/(4 w h), sampled uniformly by area.
LightSample LightSampler::sample_area(const Vec3& p, const Vec3& n, const Vec2& u) const {
  const Light& light = light_;
  LightSample s{};
  const Vec3 q = light.position + (u.x() - 0.5f) * light.size.x() * side_w_ + (u.y() - 0.5f) * light.size.y() * side_h_;
  const Vec3 to_light = q - p;
  s.distance = to_light.norm();
  const float inverse_distance = 1.0f / s.distance;
  s.direction = to_light * inverse_distance;
  const float cos_surface = n.dot(s.direction);
  const float cos_light = -axis_.dot(s.direction);
  if (cos_surface <= 0.0f || cos_light <= 0.0f) {
    s.irradiance = Vec3::Zero();
    return s;
  }
  s.irradiance = area_intensity_ * (cos_surface * cos_light * inverse_distance * inverse_distance);
  return s;
}

// Sun: irradiance on a facing surface; a disc of angular diameter angle_deg
// sampled uniformly in its cone (no u: its centre).
LightSample LightSampler::sample_directional(const Vec3& n, const Vec2* u) const {
  LightSample s{};
  s.direction = axis_;
  if (u && light_.angle_deg > 0.0f) s.direction = to_world(sample_uniform_cone(*u, cos_outer_), axis_);
  s.distance = std::numeric_limits<float>::infinity();
  s.irradiance = emission_ * std::max(0.0f, n.dot(s.direction));
  return s;
}

}  // namespace relight
