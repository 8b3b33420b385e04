#include "analysis/probe_lights.h"

#include <algorithm>
#include <cmath>

#include "core/statistics.h"

namespace relight {

namespace {

// Where the user says the light is, seen from `from`, and its angular radius.
bool expected_direction(const Light& light, const Vec3& from, Vec3& dir, float& angular_radius) {
  if (light.type == LightType::directional) {
    dir = -light.direction.normalized();
    angular_radius = radians(light.angle_deg) * 0.5f;
    return true;
  }
  const Vec3 to = light.position - from;
  const float dist = to.norm();
  if (dist < 1e-6f) return false;
  dir = to / dist;
  const float extent = light.type == LightType::area ? 0.5f * light.size.norm() : light.radius;
  angular_radius = std::asin(std::min(1.0f, extent / dist));
  return true;
}

struct PixelDirections {
  std::vector<size_t> index;
  std::vector<Vec3> direction;
};

// Every pixel of the probe whose direction is within acos(cos_max) of `axis`.
PixelDirections pixels_within(const Probe& probe, const Vec3& axis, float cos_max) {
  const ProbeFrame frame(probe.forward, probe.up);
  const Image& img = probe.image;
  PixelDirections out;
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x) {
      const auto d = probe_uv_to_direction(probe.mapping, frame, Vec2((x + 0.5f) / img.width, (y + 0.5f) / img.height));
      if (d && d->dot(axis) >= cos_max) {
        out.index.push_back(size_t(y) * img.width + x);
        out.direction.push_back(*d);
      }
    }
  return out;
}

Vec3 channel_median(std::vector<Vec3> values) {
  Vec3 m;
  for (int c = 0; c < 3; ++c) {
    std::vector<float> ch;
    for (const auto& v : values) ch.push_back(v[c]);
    std::nth_element(ch.begin(), ch.begin() + ch.size() / 2, ch.end());
    m[c] = ch[ch.size() / 2];
  }
  return m;
}

constexpr float kSearchDeg = 10.0f;  // how far the real light may be from where the user put it
constexpr float kStandOut = 4.0f;    // a light pixel is this many times brighter than its surroundings
constexpr float kHalf = 0.5f;        // of the brightest pixel: the light's own pixels
constexpr float kCandidate = 1.0f / 16.0f;  // of the brightest near where it was put: a light's pixel
constexpr float kLeak = 2.0f;               // of a spot's peak: a brighter pixel joined to it is another light
constexpr size_t kMinMiddle = 4;     // pixels wholly inside a light: fewer, and the probe does not resolve it
constexpr float kEven = 0.8f;        // of its middle's bright pixels, the dim ones: an evenly bright light

// The pixel at (x, y) of the probe, across the panorama's seam where it has
// one; nothing off the image.
std::optional<size_t> probe_pixel(const Probe& probe, int x, int y) {
  const Image& img = probe.image;
  if (y < 0 || y >= img.height) return std::nullopt;
  if (x < 0 || x >= img.width) {
    if (probe.mapping != ProbeMapping::equirect) return std::nullopt;
    x = (x + img.width) % img.width;
  }
  return size_t(y) * img.width + size_t(x);
}

// The radiance above the surroundings of the light's evenly bright middle:
// the median of the region's pixels whose eight neighbours are all at least
// half as bright as its brightest (no pixel of it partly the light, partly
// not). Nothing where there are too few such pixels (a light a few pixels
// across), or they differ (a shaded lamp, a hot spot).
std::optional<float> middle_radiance(const Probe& probe, const std::vector<size_t>& region, const Vec3& surround) {
  const Image& img = probe.image;
  const auto excess = [&](size_t p) { return luminance(img.pixels[p]) - luminance(surround); };
  float brightest = 0.0f;
  for (size_t p : region) brightest = std::max(brightest, excess(p));
  std::vector<char> bright(img.pixels.size(), 0);
  for (size_t p : region) bright[p] = excess(p) >= kHalf * brightest;
  const auto is_bright = [&](int x, int y) {
    const std::optional<size_t> p = probe_pixel(probe, x, y);
    return p && bright[*p] != 0;
  };
  std::vector<double> middle;
  for (size_t p : region) {
    const int x = int(p % img.width), y = int(p / img.width);
    bool inside = true;
    for (int dy = -1; dy <= 1; ++dy)
      for (int dx = -1; dx <= 1; ++dx) inside = inside && is_bright(x + dx, y + dy);
    if (inside) middle.push_back(excess(p));
  }
  if (middle.size() < kMinMiddle || percentile(middle, 0.1) < kEven * percentile(middle, 0.9)) return std::nullopt;
  return float(percentile(middle, 0.5));
}

struct BrightSpot {
  PixelDirections pixels;
  float peak = 0.0f;  // the brightness it was joined from
};

// The light's spot around pixel `seed` of the search cone: from `seed` up to
// the brightest pixel joined to it within the cone (neighbour by neighbour,
// across the panorama's seam too, at least half as bright as `seed`), then
// the pixels joined to that peak, in the cone or not, at least half as
// bright as it. The light's spot however large it is, and not another lamp
// beside it; nothing where it joins something much brighter than its peak
// (a patch of sky joined to the sun), which is not this light.
std::optional<BrightSpot> bright_spot(const Probe& probe, const PixelDirections& search, size_t seed) {
  const Image& img = probe.image;
  const auto brightness = [&](size_t p) { return luminance(img.pixels[p]); };
  std::vector<char> in_search(img.pixels.size(), 0);
  for (size_t p : search.index) in_search[p] = 1;
  const auto joined = [&](size_t start, float threshold, bool within_search) {
    std::vector<size_t> spot{start};
    std::vector<char> taken(img.pixels.size(), 0);
    taken[start] = 1;
    for (size_t next = 0; next < spot.size(); ++next) {
      const int x = int(spot[next] % img.width), y = int(spot[next] / img.width);
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const std::optional<size_t> p = probe_pixel(probe, x + dx, y + dy);
          if (!p || taken[*p] || brightness(*p) < threshold || (within_search && !in_search[*p])) continue;
          taken[*p] = 1;
          spot.push_back(*p);
        }
    }
    return spot;
  };
  const std::vector<size_t> climbed = joined(seed, kHalf * brightness(seed), true);
  const size_t top = *std::max_element(climbed.begin(), climbed.end(),
                                       [&](size_t a, size_t b) { return brightness(a) < brightness(b); });
  BrightSpot spot{{}, brightness(top)};
  const ProbeFrame frame(probe.forward, probe.up);
  for (size_t p : joined(top, kHalf * spot.peak, false)) {
    if (brightness(p) > kLeak * spot.peak) return std::nullopt;
    const Vec2 uv((float(p % img.width) + 0.5f) / img.width, (float(p / img.width) + 0.5f) / img.height);
    if (const auto d = probe_uv_to_direction(probe.mapping, frame, uv)) {
      spot.pixels.index.push_back(p);
      spot.pixels.direction.push_back(*d);
    }
  }
  if (spot.pixels.index.empty()) return std::nullopt;
  return spot;
}

}  // namespace

Vec3 seen_middle(const Light& light, const Vec3& from) {
  const Vec3 centre = (light.position - from).normalized();
  if (light.type != LightType::area) return centre;
  // The rectangle's irradiance at `from` on a surface facing its centre, over
  // a 16 x 16 grid of samples; the cosine there taken back out, each
  // sample's weight is its solid angle.
  constexpr int kGrid = 16;
  const LightSampler sampler(light);
  Vec3 sum = Vec3::Zero();
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const LightSample s = sampler.sample(from, centre, Vec2((i + 0.5f) / kGrid, (j + 0.5f) / kGrid));
      const float cosine = s.direction.dot(centre);
      if (cosine > 0.0f) sum += luminance(s.irradiance) / cosine * s.direction;
    }
  return sum.norm() > 0.0f ? Vec3(sum.normalized()) : centre;
}

std::optional<LightInProbe> locate_light_in_probe(const Probe& probe, const Light& light) {
  Vec3 expected;
  float radius;
  if (!light.enabled || !expected_direction(light, probe.position, expected, radius)) return std::nullopt;
  const Image& img = probe.image;

  // 1. The light's bright spot: of the pixels in the search cone around the
  //    expected direction at least a sixteenth as bright as its brightest,
  //    the one nearest that direction (another lamp a few degrees away may
  //    be brighter: a ceiling panel's 125 W/m^2/sr beside a bare bulb's 316;
  //    a wall it lights is hundreds of times dimmer); then the pixels joined
  //    to it at least half as bright as the brightest of them (`bright_spot`),
  //    and their middle by solid angle (a panel is evenly bright, and its
  //    brightest pixel anywhere on it: centred there, a ceiling panel seen
  //    from below measured 30 % low).
  const PixelDirections search = pixels_within(probe, expected, std::cos(radians(kSearchDeg) + radius));
  if (search.index.empty()) return std::nullopt;
  const auto brightness = [&](size_t i) { return luminance(img.pixels[search.index[i]]); };
  float search_brightest = 0.0f;
  for (size_t i = 0; i < search.index.size(); ++i) search_brightest = std::max(search_brightest, brightness(i));
  const float candidate = kCandidate * search_brightest;
  size_t seed = 0;
  for (size_t i = 0; i < search.index.size(); ++i)
    if (brightness(i) >= candidate &&
        (brightness(seed) < candidate || search.direction[i].dot(expected) > search.direction[seed].dot(expected)))
      seed = i;
  const auto solid_angle = [&](size_t pixel) {
    const int x = int(pixel % img.width), y = int(pixel / img.width);
    return probe_pixel_solid_angle(probe.mapping, Vec2((x + 0.5f) / img.width, (y + 0.5f) / img.height), img.width,
                                   img.height);
  };
  const std::optional<BrightSpot> found = bright_spot(probe, search, search.index[seed]);
  if (!found) return std::nullopt;
  const PixelDirections& spot = found->pixels;
  const float brightest = found->peak;
  Vec3 spot_sum = Vec3::Zero();
  for (size_t i = 0; i < spot.index.size(); ++i) spot_sum += solid_angle(spot.index[i]) * spot.direction[i];
  const Vec3 centre = spot_sum.normalized();
  float cos_spot = 1.0f;
  for (const Vec3& d : spot.direction) cos_spot = std::min(cos_spot, d.dot(centre));
  // The region's radius: the spot's angular radius, not the size given (a
  // light given a quarter of its size would leave its rim to pass for the
  // wall behind it; one given twice its size would take in the walls around
  // it, and their light for its own), plus a margin for the spot's rim
  // pixels and the probe's blur (three and a half pixels) and for a light
  // not evenly bright to its rim (one degree).
  const float pixel = std::sqrt(solid_angle(search.index[seed]));
  const float cone = std::min(kPi, std::acos(cos_spot) + 3.5f * pixel + radians(1.0f));

  // 2. The region around the centre, and the ring around it.
  const PixelDirections region = pixels_within(probe, centre, std::cos(cone));
  const PixelDirections outer = pixels_within(probe, centre, std::cos(std::min(kPi, 2.0f * cone)));
  std::vector<Vec3> ring;
  for (size_t i = 0; i < outer.index.size(); ++i)
    if (outer.direction[i].dot(centre) < std::cos(cone)) ring.push_back(img.pixels[outer.index[i]]);
  if (region.index.empty() || ring.empty()) return std::nullopt;

  LightInProbe seen;
  seen.surround = channel_median(std::move(ring));
  if (brightest < kStandOut * luminance(seen.surround) + 1e-6f) return std::nullopt;
  seen.pixels = region.index;
  seen.irradiance = Vec3::Zero();
  Vec3 weighted_direction = Vec3::Zero();
  for (size_t i = 0; i < region.index.size(); ++i) {
    const size_t p = region.index[i];
    const Vec3 excess = (img.pixels[p] - seen.surround).cwiseMax(0.0f) * solid_angle(p);
    seen.irradiance += excess;
    weighted_direction += luminance(excess) * region.direction[i];
  }
  seen.direction = weighted_direction.norm() > 0.0f ? Vec3(weighted_direction.normalized()) : centre;
  if (const auto radiance = middle_radiance(probe, region.index, seen.surround))
    seen.solid_angle = luminance(seen.irradiance) / *radiance;
  return seen;
}

Probe remove_lights_from_probe(const Probe& probe, const std::vector<Light>& lights) {
  Probe out = probe;
  for (const Light& light : lights)
    if (const auto seen = locate_light_in_probe(probe, light))
      for (size_t p : seen->pixels) out.image.pixels[p] = seen->surround;
  return out;
}

std::optional<Vec3> emission_from_probe(const Probe& probe, const Light& light, const LightInProbe& seen) {
  if (light.type == LightType::directional) return seen.irradiance;  // a sun's emission is its irradiance
  const Vec3 to_probe = probe.position - light.position;
  const float d2 = to_probe.squaredNorm();
  const Vec3 dir = to_probe.normalized();
  switch (light.type) {
    case LightType::point:  // E = P / (4 pi (d^2 + r^2))
      return Vec3(seen.irradiance * (4.0f * kPi * (d2 + light.radius * light.radius)));
    case LightType::spot: {
      const float factor = spot_factor(light, dir.dot(light.direction.normalized()));
      if (factor < 0.05f) return std::nullopt;  // the probe is (nearly) outside the cone
      return Vec3(seen.irradiance * (4.0f * kPi * (d2 + light.radius * light.radius) / factor));
    }
    case LightType::area: {  // E = L Omega, L = P / (4 w h), Omega the rectangle's solid angle
      const float cos_light = dir.dot(light.direction.normalized());
      if (cos_light < 0.1f) return std::nullopt;
      const float omega = area_light_solid_angle(light, probe.position);
      if (!(omega > 0.0f)) return std::nullopt;
      return Vec3(seen.irradiance * (4.0f * light.size.x() * light.size.y() / omega));
    }
    case LightType::directional: break;
  }
  return std::nullopt;
}

std::optional<float> distance_from_apparent_size(const Probe& probe, const Light& light, const LightInProbe& seen,
                                                 const Vec3& direction) {
  if (!seen.solid_angle) return std::nullopt;
  const float omega = *seen.solid_angle;
  switch (light.type) {
    case LightType::point:
    case LightType::spot: {  // a sphere of radius r at distance d fills 2 pi (1 - cos asin(r / d))
      const float cos_edge = 1.0f - omega / (2.0f * kPi);
      if (light.radius <= 0.0f || !(cos_edge > 0.0f && cos_edge < 1.0f)) return std::nullopt;
      return light.radius / std::sqrt(1.0f - cos_edge * cos_edge);
    }
    case LightType::area: {  // the rectangle, facing as given, fills less the farther it is
      const auto fills = [&](float distance) {
        Light placed = light;
        placed.position = probe.position + distance * direction;
        return area_light_solid_angle(placed, probe.position);
      };
      float nearer = 0.01f, farther = 1000.0f;  // m
      if (!(fills(nearer) > omega && fills(farther) < omega)) return std::nullopt;
      for (int i = 0; i < 40; ++i) {
        const float middle = std::sqrt(nearer * farther);
        (fills(middle) > omega ? nearer : farther) = middle;
      }
      return std::sqrt(nearer * farther);
    }
    case LightType::directional:
      break;
  }
  return std::nullopt;
}

std::optional<float> size_seen_over_given(const Probe& probe, const Light& light, const LightInProbe& seen) {
  const Vec3 to_light = light.position - probe.position;
  const float distance = to_light.norm();
  if (!(distance > 0.0f)) return std::nullopt;
  const auto filled_at = distance_from_apparent_size(probe, light, seen, to_light / distance);
  if (!filled_at) return std::nullopt;
  return distance / *filled_at;
}

bool sizes_agree(float ratio) {
  constexpr float kAgree = 1.5f;
  return ratio <= kAgree && kAgree * ratio >= 1.0f;
}

std::optional<Vec3> triangulate(const Vec3& a, const Vec3& u, const Vec3& b, const Vec3& v) {
  // Closest points a + s u and b + t v of two lines (u, v unit).
  const Vec3 w = a - b;
  const float uv = u.dot(v), denom = 1.0f - uv * uv;
  if (denom < 1e-6f) return std::nullopt;
  const float s = (uv * v.dot(w) - u.dot(w)) / denom;
  const float t = (v.dot(w) - uv * u.dot(w)) / denom;
  if (s <= 0.0f || t <= 0.0f) return std::nullopt;  // behind a probe
  return Vec3(0.5f * ((a + s * u) + (b + t * v)));
}

}  // namespace relight
