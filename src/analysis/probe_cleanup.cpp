#include "analysis/probe_cleanup.h"

#include <algorithm>
#include <cmath>

namespace relight {

namespace {

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

std::optional<Probe> remove_local_geometry_from_probe(const Probe& probe, const RayScene& rays,
                                                      const std::optional<Vec3>& fill) {
  Probe out = probe;
  const ProbeFrame frame(probe.forward, probe.up);
  const int w = probe.image.width, h = probe.image.height;
  std::vector<uint8_t> hole(size_t(w) * h, 0), outside(size_t(w) * h, 0);
  size_t known = 0;
  SurfacePoint hit;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (!probe_uv_to_direction(probe.mapping, frame, Vec2((x + 0.5f) / w, (y + 0.5f) / h))) {
        outside[i] = 1;
        continue;
      }
      // A pixel is the mean over its square: one whose square shows any
      // geometry (a silhouette, the horizon) mixes the two, so it goes too.
      for (int k = 0; k < 9 && !hole[i]; ++k) {
        const Vec2 uv((x + 0.5f * float(k % 3)) / w, (y + 0.5f * float(k / 3)) / h);
        const auto d = probe_uv_to_direction(probe.mapping, frame, uv);
        hole[i] = d && rays.intersect(probe.position, *d, hit);
      }
      known += !hole[i];
    }
  if (known == 0) return std::nullopt;
  if (fill) {
    for (size_t i = 0; i < hole.size(); ++i)
      if (hole[i]) out.image.pixels[i] = *fill;
  } else {
    fill_holes(out.image, hole, outside, probe.mapping == ProbeMapping::equirect);
  }
  return out;
}

Vec3 mean_radiance(const Probe& probe) {
  const ProbeFrame frame(probe.forward, probe.up);
  const int w = probe.image.width, h = probe.image.height;
  Vec3 sum = Vec3::Zero();
  double total = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const Vec2 uv((x + 0.5f) / w, (y + 0.5f) / h);
      if (!probe_uv_to_direction(probe.mapping, frame, uv)) continue;
      const float sr = probe_pixel_solid_angle(probe.mapping, uv, w, h);
      sum += sr * probe.image.at(x, y);
      total += sr;
    }
  return total > 0.0 ? Vec3(sum / float(total)) : Vec3::Zero();
}

}  // namespace relight
