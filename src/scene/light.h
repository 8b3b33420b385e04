// Light: the four light types of FORMAT.md with exactly its radiometry
// (Blender Cycles 3.x units), and the sampling of the irradiance a light
// delivers to a surface point.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "core/vec.h"

namespace relight {

enum class LightType { point, spot, area, directional };

const char* to_string(LightType type);

// How a keyed value goes from one key to the next (animation.h).
enum class Interpolation { constant, linear, smooth };
const char* to_string(Interpolation interpolation);

// A light's values at one frame of an animated rig: those it sets are keyed
// there, the others are keyed at other frames or not at all (FORMAT.md
// extension, docs/formats.md "Animated rigs").
struct LightKey {
  int frame = 0;
  Interpolation interpolation = Interpolation::smooth;  // towards the next key
  std::optional<Vec3> position, direction, color;
  std::optional<float> power;  // W, or W/m^2 for a sun (its irradiance)
  std::optional<bool> enabled;
};

struct Light {
  LightType type = LightType::point;
  std::string name;
  Vec3 color = Vec3::Ones();
  bool enabled = true;
  Vec3 position = Vec3::Zero();
  Vec3 direction = Vec3(0, 0, -1);  // spot/area: where it points; sun: the way light travels
  Vec3 up = Vec3(0, 0, 1);          // area: orients the h side
  float power = 0.0f;               // W (point, spot, area)
  float irradiance = 0.0f;          // W/m^2 (directional)
  float radius = 0.0f;              // m (point, spot)
  float spot_angle_deg = 45.0f;     // full cone angle
  float blend = 0.0f;
  Vec2 size = Vec2(1, 1);           // m (area)
  float angle_deg = 0.0f;           // angular diameter (directional)
  // An animated rig's keys, by frame; none: the light holds still. The
  // values above are the light's outside a frame sequence (relight studio).
  std::vector<LightKey> keys;

  // The light's emission scale: color x power (or x irradiance).
  Vec3 emission() const { return color * (type == LightType::directional ? irradiance : power); }
};

// Whether two versions of a light differ in what their unit-emission images
// depend on: everything but colour, power (irradiance), enabled and name.
bool same_geometry(const Light& a, const Light& b);

// An area light's unit sides: w along direction x up, h = w x direction.
struct AreaLightSides {
  Vec3 w, h;
};
AreaLightSides area_light_sides(const Light& light);

// The solid angle (sr) an area light's rectangle covers seen from `from`,
// exactly (the small-light limit w h cos / d^2 overstates it for a light
// near the viewpoint).
float area_light_solid_angle(const Light& light, const Vec3& from);

// One sample of a light as seen from a surface point.
struct LightSample {
  Vec3 direction;      // unit, from the surface point towards the light
  float distance;      // to the sampled point on the light (infinity for the sun)
  Vec3 irradiance;     // unbiased estimate of the light's irradiance at the point, unoccluded
};

// A light prepared for sampling from many points: its per-light constants
// (normalised axes, cone cosine, emission) worked out once.
class LightSampler {
 public:
  explicit LightSampler(const Light& light);
  // Samples the light from point p with unit normal n; u in [0,1)^2. The
  // irradiance is zero when the light is behind the surface or outside a cone.
  LightSample sample(const Vec3& p, const Vec3& n, const Vec2& u) const;
  // False where every u gives the same sample (a point or spot without
  // radius, a sun without angle): one sample is then exact.
  bool needs_random() const;
  // An area light: the irradiance its rectangle sends to p (unit normal n)
  // with nothing in the way, exactly (Lambert's formula for a polygon, over
  // the part above p's horizon): what sample() estimates, without its noise.
  Vec3 unshadowed_irradiance(const Vec3& p, const Vec3& n) const;
  // The light's irradiance at p with nothing in the way, as its centre
  // sends it, and the direction and distance to that centre: for a point,
  // spot or sun of any size, its irradiance without noise; for an area
  // light, one sample's (unshadowed_irradiance is its exact irradiance).
  LightSample unshadowed_from_centre(const Vec3& p, const Vec3& n) const;
  // The unit direction from p towards the light's centre (a sun's: towards
  // the sun); +z at the centre itself.
  Vec3 direction_to_centre(const Vec3& p) const;
  const Light& light() const { return light_; }

 private:
  LightSample sample_point_like(const Vec3& p, const Vec3& n, const Vec2* u) const;
  LightSample sample_area(const Vec3& p, const Vec3& n, const Vec2& u) const;
  LightSample sample_directional(const Vec3& n, const Vec2* u) const;

  Light light_;
  Vec3 emission_;
  Vec3 axis_;               // spot/area: unit direction; sun: unit direction towards it
  float cos_outer_ = -1.0f; // spot: cos(spot_angle/2); sun: cos(angle/2)
  Vec3 side_w_, side_h_;    // area: the w and h sides, unit
  Vec3 area_intensity_;     // area: its radiance times its area
};

// Samples the light from point p with unit normal n; u in [0,1)^2 (one
// sample of LightSampler(light)).
inline LightSample sample_light(const Light& light, const Vec3& p, const Vec3& n, const Vec2& u) {
  return LightSampler(light).sample(p, n, u);
}

// Spot cone factor c*s of FORMAT.md for the cosine c between the spot
// direction and the direction from the light to the point.
float spot_factor(const Light& light, float cos_theta);

}  // namespace relight
