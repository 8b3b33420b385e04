#include "render/direct_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

#include "core/sampling.h"

namespace relight {

PixelSurfaces PixelSurfaces::central_samples(const GBuffer& gbuffer) {
  PixelSurfaces s;
  s.width = gbuffer.width();
  s.height = gbuffer.height();
  s.surface.resize(size_t(s.width) * s.height);
  s.hit.resize(s.surface.size());
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const GBufferSample& g = gbuffer.central(x, y);
      const size_t i = size_t(y) * s.width + x;
      s.surface[i] = g.surface;
      s.hit[i] = g.hit;
    }
  return s;
}

Light unit_light(const Light& light) {
  Light unit = light;
  unit.color = Vec3::Ones();
  unit.power = 1.0f;
  unit.irradiance = 1.0f;
  unit.enabled = true;
  return unit;
}

namespace {

// Per-thread state of one row: its pixels' sums and the packet of shadow
// rays being filled, with each ray's light sample and pixel.
struct RowRays {
  std::vector<int> samples;  // per pixel: surface samples x light samples
  std::vector<Vec3> sum;
  // Per pixel, for DirectLightSettings::exact_unshadowed: the samples'
  // irradiance (summed over the channels), blocked or not, and the exact
  // unshadowed irradiance summed over the surface samples.
  std::vector<float> offered;
  std::vector<Vec3> exact;
  ShadowPacket packet;
  Vec3 irradiance[ShadowPacket::kCapacity];  // unoccluded, of each ray's light sample
  int column[ShadowPacket::kCapacity];

  // Traces the packet and adds the light of the rays nothing blocks.
  void trace(const RayScene& scene) {
    scene.occluded(packet);
    for (int j = 0; j < packet.size(); ++j)
      if (!packet.blocked(j)) sum[size_t(column[j])] += irradiance[j];
    packet.clear();
  }
};

// surface_at(pixel, k): the pixel's k-th surface sample, nullptr where it
// sees the background. A row's rays go to Embree as packets of neighbouring
// pixels', traced as soon as one is full.
template <class SurfaceAt>
bool trace_direct_light(int width, int height, int samples_per_pixel, const SurfaceAt& surface_at,
                        const RayScene& scene, const Light& light, const DirectLightSettings& settings, Image& out,
                        const std::atomic<bool>* cancel) {
  if (out.width != width || out.height != height) out = Image(width, height);
  const LightSampler sampler(light);
  // A light without extent gives the same sample whatever the random numbers.
  const bool random = sampler.needs_random();
  const int light_samples = random ? std::max(1, settings.light_samples) : 1;
  const bool ratio = settings.exact_unshadowed && light.type == LightType::area;
  // The ratio's bias grows with the spread of its sums: its samples are
  // stratified over the rectangle, a strata x strata grid of cells (where
  // the samples make a square number).
  const int grid = int(std::lround(std::sqrt(float(light_samples))));
  const int strata = ratio && grid * grid == light_samples ? grid : 1;
  std::atomic<bool> stopped{false};
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    thread_local RowRays row;
    for (int y = rows.begin(); y != rows.end(); ++y) {
      if (cancel && cancel->load(std::memory_order_relaxed)) {
        stopped = true;
        return;
      }
      row.samples.assign(size_t(width), 0);
      row.sum.assign(size_t(width), Vec3::Zero());
      if (ratio) {
        row.offered.assign(size_t(width), 0.0f);
        row.exact.assign(size_t(width), Vec3::Zero());
      }
      for (int x = 0; x < width; ++x) {
        const size_t pixel = size_t(y) * width + x;
        std::optional<Rng> rng;
        if (random) rng.emplace(settings.seed, pixel, settings.pass);
        for (int k = 0; k < samples_per_pixel; ++k) {
          const SurfacePoint* p = surface_at(pixel, k);
          if (!p) continue;
          if (ratio) row.exact[size_t(x)] += sampler.unshadowed_irradiance(p->position, p->normal);
          for (int j = 0; j < light_samples; ++j) {
            ++row.samples[size_t(x)];
            Vec2 u = random ? rng->uniform2() : Vec2(0.5f, 0.5f);
            if (strata > 1) u = (Vec2(float(j % strata), float(j / strata)) + u) / float(strata);
            const LightSample s = sampler.sample(p->position, p->normal, u);
            if (s.irradiance.isZero()) continue;
            if (ratio) row.offered[size_t(x)] += s.irradiance.sum();
            const int slot = row.packet.add(scene.shadow_ray(*p, s.direction, s.distance));
            row.irradiance[slot] = s.irradiance;
            row.column[slot] = x;
            if (row.packet.full()) row.trace(scene);
          }
        }
      }
      if (row.packet.size()) row.trace(scene);
      for (int x = 0; x < width; ++x) {
        const size_t i = size_t(x);
        const int n = row.samples[i];
        if (ratio) {  // the mean exact irradiance over the surface samples, times the unblocked share
          const float surfaces = float(n / light_samples), offered = row.offered[i];
          out.at(x, y) =
              offered > 0.0f ? Vec3(row.exact[i] * (row.sum[i].sum() / offered * kInvPi / surfaces)) : Vec3::Zero();
        } else {
          out.at(x, y) = n ? Vec3(row.sum[i] * (kInvPi / float(n))) : Vec3::Zero();
        }
      }
    }
  });
  return !stopped;
}

}  // namespace

bool render_direct_light(const PixelSurfaces& surfaces, const RayScene& rays, const Light& light,
                         const DirectLightSettings& settings, Image& out, const std::atomic<bool>* cancel) {
  const auto surface_at = [&](size_t pixel, int) -> const SurfacePoint* {
    return surfaces.hit[pixel] ? &surfaces.surface[pixel] : nullptr;
  };
  return trace_direct_light(surfaces.width, surfaces.height, 1, surface_at, rays, light, settings, out, cancel);
}

bool render_direct_light(const GBuffer& gbuffer, const RayScene& rays, const Light& light,
                         const DirectLightSettings& settings, Image& out, const std::atomic<bool>* cancel) {
  const int w = gbuffer.width(), spp = gbuffer.samples_per_pixel();
  const auto surface_at = [&](size_t pixel, int k) -> const SurfacePoint* {
    const GBufferSample& s = gbuffer.sample(int(pixel % w), int(pixel / w), k);
    return s.hit ? &s.surface : nullptr;
  };
  return trace_direct_light(w, gbuffer.height(), spp, surface_at, rays, light, settings, out, cancel);
}

void CpuDirectLight::render(const Light& light, Image& out) {
  DirectLightSettings settings;
  settings.seed = seed_;
  render_direct_light(surfaces_, rays_, light, settings, out);
}

}  // namespace relight
