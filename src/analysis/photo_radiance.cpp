#include "analysis/photo_radiance.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "analysis/probe_lights.h"

namespace relight {

namespace {

constexpr double kMinPlateauShare = 5e-4;  // of the pixels, at the largest value: clipped
constexpr float kSameDistance = 0.01f;     // a point and what a pixel shows: this close, relative

// Not clipped, finite, not negative.
bool faithful(const Vec3& v, const std::optional<float>& clip) {
  return v.allFinite() && v.minCoeff() >= 0.0f && (!clip || v.maxCoeff() < *clip);
}

}  // namespace

std::optional<float> photo_clip_level(const Image& image) {
  float top = 0.0f;
  for (const Vec3& p : image.pixels)
    if (p.allFinite()) top = std::max(top, p.maxCoeff());
  if (top <= 0.0f) return std::nullopt;
  size_t at_top = 0;
  for (const Vec3& p : image.pixels) at_top += p.allFinite() && p.maxCoeff() >= top;
  if (double(at_top) < kMinPlateauShare * double(image.size())) return std::nullopt;
  return top;
}

PhotoRadiance::PhotoRadiance(const Camera& camera, const GBuffer& gbuffer, const Image& photo,
                             const std::vector<Probe>& probes, const RayScene& rays, const std::vector<Light>& lights)
    : camera_(camera), gbuffer_(gbuffer), photo_(photo), usable_(photo.size(), 0) {
  const std::optional<float> clip = photo_clip_level(photo);
  size_t seen = 0, usable = 0;
  for (int y = 0; y < photo.height; ++y)
    for (int x = 0; x < photo.width; ++x) {
      if (gbuffer.coverage(x, y) <= 0.0f) continue;
      ++seen;
      if (!faithful(photo.at(x, y), clip) || !gbuffer.one_surface(x, y)) continue;
      usable_[size_t(y) * photo.width + x] = 1;
      ++usable;
    }
  usable_share_ = seen ? double(usable) / double(seen) : 0.0;
  for (const Probe& probe : probes) probes_.push_back(view_of(probe, rays, lights));
}

PhotoRadiance::ProbeView PhotoRadiance::view_of(const Probe& probe, const RayScene& rays,
                                                const std::vector<Light>& lights) {
  const int w = probe.image.width, h = probe.image.height;
  ProbeView view{&probe, ProbeFrame(probe.forward, probe.up), std::vector<uint8_t>(size_t(w) * h, 0),
                 std::vector<SurfacePoint>(size_t(w) * h)};
  const std::optional<float> clip = photo_clip_level(probe.image);
  tbb::parallel_for(0, h, [&](int y) {
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (!faithful(probe.image.pixels[i], clip)) continue;
      // The pixel's centre, corners and edge midpoints all on one surface.
      const auto hit_at = [&](int k, SurfacePoint& hit) {
        const Vec2 uv((x + 0.5f * float(k % 3)) / w, (y + 0.5f * float(k / 3)) / h);
        const auto d = probe_uv_to_direction(probe.mapping, view.frame, uv);
        return d && rays.intersect(probe.position, *d, hit);
      };
      bool one = hit_at(4, view.centre[i]);
      SurfacePoint hit;
      for (int k = 0; k < 9 && one; ++k) one = k == 4 || (hit_at(k, hit) && GBuffer::same_surface(view.centre[i], hit));
      view.usable[i] = one;
    }
  });
  // A probe sees the lights in front of what is behind them.
  for (const Light& light : lights)
    if (light.enabled)
      if (const auto seen = locate_light_in_probe(probe, light))
        for (size_t p : seen->pixels) view.usable[p] = 0;
  return view;
}

std::optional<Vec3> PhotoRadiance::from_probe(const ProbeView& view, const SurfacePoint& p) const {
  const Probe& probe = *view.probe;
  const Vec3 to_probe = probe.position - p.position;
  if (to_probe.dot(p.geometric_normal) <= 0.0f) return std::nullopt;
  const float dist = to_probe.norm();
  if (dist <= 0.0f) return std::nullopt;
  const Vec2 uv = probe_direction_to_uv(probe.mapping, view.frame, -to_probe / dist);
  const int w = probe.image.width, h = probe.image.height;
  const int x = std::clamp(int(uv.x() * w), 0, w - 1), y = std::clamp(int(uv.y() * h), 0, h - 1);
  const size_t i = size_t(y) * w + x;
  if (!view.usable[i]) return std::nullopt;
  const SurfacePoint& c = view.centre[i];
  if (c.prim != p.prim && std::abs(c.distance - dist) > kSameDistance * dist) return std::nullopt;
  return probe.image.pixels[i];
}

std::vector<TriangleAlbedo> PhotoRadiance::probe_albedo(const Integrator& integrator,
                                                        const std::vector<uint8_t>& wanted, int paths,
                                                        uint64_t seed) const {
  struct Point {
    const SurfacePoint* surface;
    Vec3 radiance, illumination = Vec3::Zero();
  };
  std::vector<Point> points;
  for (const ProbeView& view : probes_)
    for (size_t i = 0; i < view.usable.size(); ++i)
      if (view.usable[i] && view.centre[i].prim < wanted.size() && wanted[view.centre[i].prim])
        points.push_back({&view.centre[i], view.probe->image.pixels[i]});
  tbb::parallel_for(size_t(0), points.size(), [&](size_t n) {
    Rng rng(seed ^ 0x70726f6265ull, n);
    for (int k = 0; k < paths; ++k) points[n].illumination += integrator.illumination(*points[n].surface, rng);
    points[n].illumination /= float(paths);
  });
  std::vector<Vec3> radiance(wanted.size(), Vec3::Zero()), illumination(wanted.size(), Vec3::Zero());
  for (const Point& p : points) {
    radiance[p.surface->prim] += p.radiance;
    illumination[p.surface->prim] += p.illumination;
  }
  std::vector<TriangleAlbedo> out;
  for (uint32_t t = 0; t < wanted.size(); ++t)
    if (illumination[t].minCoeff() > 0.0f) out.push_back({t, radiance[t].cwiseQuotient(illumination[t])});
  return out;
}

std::optional<Vec3> PhotoRadiance::at(const SurfacePoint& p) const {
  if (const auto pixel = gbuffer_.pixel_showing(camera_, p);
      pixel && usable_[size_t(pixel->y) * photo_.width + pixel->x])
    return photo_.at(pixel->x, pixel->y);
  for (const ProbeView& view : probes_)
    if (auto radiance = from_probe(view, p)) return radiance;
  return std::nullopt;
}

}  // namespace relight
