#include "analysis/probe_cleanup.h"

#include <algorithm>
#include <cmath>

namespace relight {

namespace {

// Direction from the probe to the light and the light's angular radius there.
bool light_direction(const Light& light, const Vec3& from, Vec3& dir, float& angular_radius) {
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

// Fills the pixels marked `hole` from their known neighbours, one ring per
// pass (equirect images wrap around horizontally). Pixels marked `outside`
// (off a mirror ball's disc) are neither used nor filled.
void fill_holes(Image& img, std::vector<uint8_t>& hole, const std::vector<uint8_t>& outside, bool wrap_x) {
  const int w = img.width, h = img.height;
  for (bool changed = true; changed;) {
    changed = false;
    std::vector<std::pair<size_t, Vec3>> updates;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        if (!hole[i]) continue;
        Vec3 sum = Vec3::Zero();
        int n = 0;
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            int nx = x + dx;
            const int ny = y + dy;
            if (ny < 0 || ny >= h) continue;
            if (wrap_x) nx = (nx + w) % w;
            if (nx < 0 || nx >= w) continue;
            const size_t j = size_t(ny) * w + nx;
            if (hole[j] || outside[j]) continue;
            sum += img.pixels[j];
            ++n;
          }
        if (n) updates.emplace_back(i, sum / float(n));
      }
    for (const auto& [i, v] : updates) {
      img.pixels[i] = v;
      hole[i] = 0;
      changed = true;
    }
  }
}

}  // namespace

Probe remove_local_geometry_from_probe(const Probe& probe, const RayScene& rays) {
  Probe out = probe;
  const ProbeFrame frame(probe.forward, probe.up);
  const int w = probe.image.width, h = probe.image.height;
  std::vector<uint8_t> hole(size_t(w) * h, 0), outside(size_t(w) * h, 0);
  size_t holes = 0, known = 0;
  SurfacePoint hit;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const auto d = probe_uv_to_direction(probe.mapping, frame, Vec2((x + 0.5f) / w, (y + 0.5f) / h));
      if (!d) {
        outside[i] = 1;
        continue;
      }
      hole[i] = rays.intersect(probe.position, *d, hit);
      (hole[i] ? holes : known)++;
    }
  if (known == 0) return out;  // the probe sees only geometry: nothing distant to keep
  fill_holes(out.image, hole, outside, probe.mapping == ProbeMapping::equirect);
  return out;
}

Probe remove_lights_from_probe(const Probe& probe, const std::vector<Light>& lights) {
  Probe out = probe;
  const ProbeFrame frame(probe.forward, probe.up);
  const Image& img = probe.image;
  for (const Light& light : lights) {
    if (!light.enabled) continue;
    Vec3 dir;
    float radius;
    if (!light_direction(light, probe.position, dir, radius)) continue;
    // Margin: blur of the probe's pixels around the disc, plus a degree for
    // the user's estimate of where the light is.
    const Vec2 uv = probe_direction_to_uv(probe.mapping, frame, dir);
    const float pixel_angle = std::sqrt(probe_pixel_solid_angle(probe.mapping, uv, img.width, img.height));
    const float cone = radius + 3.0f * pixel_angle + radians(1.0f);
    const float cos_cone = std::cos(cone), cos_ring = std::cos(std::min(kPi, 2.0f * cone));

    std::vector<size_t> inside;
    std::vector<Vec3> ring;
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x) {
        const auto d = probe_uv_to_direction(probe.mapping, frame, Vec2((x + 0.5f) / img.width, (y + 0.5f) / img.height));
        if (!d) continue;
        const float c = d->dot(dir);
        if (c >= cos_cone) inside.push_back(size_t(y) * img.width + x);
        else if (c >= cos_ring) ring.push_back(img.at(x, y));
      }
    if (inside.empty() || ring.empty()) continue;
    Vec3 fill;
    for (int c = 0; c < 3; ++c) {
      std::vector<float> channel;
      for (const auto& r : ring) channel.push_back(r[c]);
      std::nth_element(channel.begin(), channel.begin() + channel.size() / 2, channel.end());
      fill[c] = channel[channel.size() / 2];
    }
    for (size_t i : inside) out.image.pixels[i] = fill;
  }
  return out;
}

}  // namespace relight
