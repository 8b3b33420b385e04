#include "render/direct_light.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <cmath>
#include <optional>

#include "core/sampling.h"

namespace relight {

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

// surface_at(pixel, k): the pixel's k-th surface sample, none where it sees
// the background. A row's rays go to Embree as packets of neighbouring
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
          const std::optional<SurfacePoint> p = surface_at(pixel, k);
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
  const auto surface_at = [&](size_t pixel, int) -> std::optional<SurfacePoint> {
    if (!surfaces.hit[pixel]) return std::nullopt;
    return surfaces.surface[pixel];
  };
  return trace_direct_light(surfaces.width, surfaces.height, 1, surface_at, rays, light, settings, out, cancel);
}

bool render_direct_light(const GBuffer& gbuffer, const RayScene& rays, const Light& light,
                         const DirectLightSettings& settings, Image& out, const std::atomic<bool>* cancel) {
  const int w = gbuffer.width(), spp = gbuffer.samples_per_pixel();
  // The G-buffer gives its samples by value (most are recomputed from their
  // rays), so they are passed on by value too.
  const auto surface_at = [&](size_t pixel, int k) -> std::optional<SurfacePoint> {
    const GBufferSample s = gbuffer.sample(int(pixel % w), int(pixel / w), k);
    if (!s.hit) return std::nullopt;
    return s.surface;
  };
  return trace_direct_light(w, gbuffer.height(), spp, surface_at, rays, light, settings, out, cancel);
}

namespace {

// What the checkerboard knows of a pixel's light.
enum Visibility : uint8_t {
  kBlocked,  // something is in the way
  kSeen,     // the light reaches the surface
  kUnlit,    // no light to shadow: the background, or a surface facing away
  kOpen,     // still to decide
};

// Whether q's surface continues p's across the pixel between them: the same
// triangle, or one whose normal and plane agree with p's, so that no
// silhouette or crease lies between them.
bool continues(const SurfacePoint& p, const SurfacePoint& q) {
  if (p.prim == q.prim) return true;
  const Vec3 d = q.position - p.position;
  const float height = p.normal.dot(d);
  return p.normal.dot(q.normal) >= 0.9f && height * height <= 0.01f * d.squaredNorm();
}

// The four neighbours of a pixel, in the order of the bits of
// CpuDirectLight's continuity masks.
constexpr int kNeighbourOffsets[4][2] = {{-1, 0}, {1, 0}, {0, -1}, {0, 1}};

// What a pixel's four neighbours (the checkerboard's first half) say of it.
struct Neighbours {
  Visibility agreed = kOpen;  // the visibility all share, all on the pixel's surface; else kOpen
  bool smooth = false;        // and their unshadowed light within 20 % of each other
  Vec3 mean_light = Vec3::Zero();
};

// `continuing`: bit k set where neighbour k continues the pixel's surface.
Neighbours neighbours_of(int width, uint8_t continuing, const std::vector<uint8_t>& visibility, const Image& light,
                         size_t i) {
  Neighbours n;
  if (continuing != 0xF) return n;  // a silhouette or crease beside it, or the view's border
  float lowest = std::numeric_limits<float>::infinity(), highest = 0.0f;
  for (const auto& [dx, dy] : kNeighbourOffsets) {
    const size_t j = i + ptrdiff_t(dy) * width + dx;
    const auto v = Visibility(visibility[j]);
    if (v == kOpen || (n.agreed != kOpen && v != n.agreed)) return {};
    n.agreed = v;
    const Vec3& e = light.pixels[j];
    n.mean_light += e;
    lowest = std::min(lowest, e.sum());
    highest = std::max(highest, e.sum());
  }
  n.smooth = highest <= 1.2f * lowest;
  n.mean_light *= 0.25f;
  return n;
}

// Where a pixel's shadow ray goes while the light moves. A light with an
// extent is aimed at one of a fixed set of points spread over it, picked by
// a hash of the pixel's index, so that a pixel costs no random numbers,
// trigonometry or frame of its own, and the pattern of a soft shadow's
// noise holds still as the light moves; one without, at its centre.
class LightTargets {
 public:
  static constexpr int kCount = 64;

  explicit LightTargets(const LightSampler& sampler) : sampler_(sampler) {
    const Light& light = sampler.light();
    for (int k = 0; k < kCount; ++k) {
      u_[k] = hammersley(k, kCount);
      if (light.type == LightType::directional)  // the same from everywhere
        sun_[k] = sampler.sample(Vec3::Zero(), -light.direction.normalized(), u_[k]).direction;
      // A point of the unit 3-sphere in 4 dimensions (the squared length of
      // its first pair uniform, both pairs' angles uniform), its first three
      // coordinates kept: seen along any direction, these points lie evenly
      // over the unit disc (Archimedes' hat-box theorem one dimension up),
      // as a sphere light's disc is sampled; so a pixel needs no frame.
      const float a = u_[k].x(), turn = 2.0f * kPi * u_[k].y();
      const float second_turn = 2.0f * kPi * (float(k) * 0.618034f - std::floor(float(k) * 0.618034f));
      ball_[k] = Vec3(std::sqrt(a) * std::cos(turn), std::sqrt(a) * std::sin(turn),
                      std::sqrt(1.0f - a) * std::cos(second_turn));
    }
  }
  // Pixel i's light at p with nothing in the way (for an area light, that of
  // its point's; for the others, from their centre, without noise) and its
  // shadow ray.
  std::pair<Vec3, ShadowRay> aim(size_t pixel, const SurfacePoint& p, const RayScene& rays) const {
    const int k = int((uint32_t(pixel) * 2654435761u) >> 26);  // Knuth's multiplicative hash, 6 bits
    const Light& light = sampler_.light();
    if (light.type == LightType::area) {
      const LightSample s = sampler_.sample(p.position, p.normal, u_[k]);
      return {s.irradiance, rays.shadow_ray(p, s.direction, s.distance)};
    }
    const LightSample s = sampler_.unshadowed_from_centre(p.position, p.normal);
    if (light.type == LightType::directional) return {s.irradiance, rays.shadow_ray(p, sun_[k], s.distance)};
    if (light.radius <= 0.0f) return {s.irradiance, rays.shadow_ray(p, s.direction, s.distance)};
    // A point of the disc facing p.
    const Vec3& q = ball_[k];
    return {s.irradiance,
            rays.shadow_ray_to(p, light.position + light.radius * (q - q.dot(s.direction) * s.direction))};
  }

 private:
  static_assert(kCount == 64, "aim() hashes a pixel to 6 bits");
  const LightSampler& sampler_;
  Vec2 u_[kCount];
  Vec3 sun_[kCount], ball_[kCount];
};

// Per-thread state of one row: the packet of shadow rays being filled and
// each ray's pixel.
struct RowVisibility {
  ShadowPacket packet;
  size_t pixel[ShadowPacket::kCapacity];
  size_t traced = 0;

  // Traces the packet; a pixel whose ray is blocked gets no light.
  void trace(const RayScene& scene, std::vector<uint8_t>& visibility, Image& light) {
    scene.occluded(packet);
    for (int j = 0; j < packet.size(); ++j) {
      const bool blocked = packet.blocked(j);
      visibility[pixel[j]] = blocked ? kBlocked : kSeen;
      if (blocked) light.pixels[pixel[j]] = Vec3::Zero();
    }
    traced += size_t(packet.size());
    packet.clear();
  }
};

}  // namespace

CpuDirectLight::CpuDirectLight(const PixelSurfaces& surfaces, const RayScene& rays)
    : surfaces_(surfaces), rays_(rays), continuing_(surfaces.surface.size(), 0) {
  const int width = surfaces.width, height = surfaces.height;
  tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y != rows.end(); ++y)
      for (int x = 0; x < width; ++x) {
        const size_t i = size_t(y) * width + x;
        if (!surfaces.hit[i]) continue;
        for (int k = 0; k < 4; ++k) {
          const int nx = x + kNeighbourOffsets[k][0], ny = y + kNeighbourOffsets[k][1];
          if (nx < 0 || ny < 0 || nx >= width || ny >= height) continue;
          const size_t j = size_t(ny) * width + nx;
          if (surfaces.hit[j] && continues(surfaces.surface[i], surfaces.surface[j])) continuing_[i] |= uint8_t(1 << k);
        }
      }
  });
}

size_t CpuDirectLight::render_counting_rays(const Light& light, Image& out) {
  const PixelSurfaces& surfaces = surfaces_;
  const RayScene& rays = rays_;
  const int width = surfaces.width, height = surfaces.height;
  if (out.width != width || out.height != height) out = Image(width, height);
  const LightSampler sampler(light);
  const bool noisy_light = light.type == LightType::area;  // its light is one sample's
  const LightTargets targets(sampler);
  // Kept from frame to frame (no allocation per frame); named through a
  // reference so that the pool's threads use the caller's.
  thread_local std::vector<uint8_t> kept;
  std::vector<uint8_t>& visibility = kept;
  visibility.assign(surfaces.surface.size(), kUnlit);
  std::atomic<size_t> traced{0};
  // Pass 0: the pixels with x + y even, each its light and its ray. Pass 1:
  // the others, settled by their neighbours (all of pass 0) where they can be.
  for (int pass = 0; pass < 2; ++pass) {
    tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
      thread_local RowVisibility row;
      row.traced = 0;
      for (int y = rows.begin(); y != rows.end(); ++y) {
        for (int x = (y + pass) % 2; x < width; x += 2) {
          const size_t i = size_t(y) * width + x;
          if (!surfaces.hit[i]) {
            out.pixels[i] = Vec3::Zero();
            continue;
          }
          const SurfacePoint& p = surfaces.surface[i];
          const Neighbours around = pass == 1 ? neighbours_of(width, continuing_[i], visibility, out, i) : Neighbours{};
          // Unlit or blocked neighbours' light is 0: the pixel's is too. An
          // area light's light is one sample's, noisy: its mean is the better.
          if (around.agreed != kOpen && (around.agreed != kSeen || around.smooth || noisy_light)) {
            out.pixels[i] = around.mean_light;
            visibility[i] = around.agreed;
            continue;
          }
          const auto [irradiance, ray] = targets.aim(i, p, rays);
          out.pixels[i] = irradiance * kInvPi;
          if (irradiance.isZero()) continue;  // kUnlit
          if ((visibility[i] = around.agreed) != kOpen) continue;
          const int slot = row.packet.add(ray);
          row.pixel[slot] = i;
          if (row.packet.full()) row.trace(rays, visibility, out);
        }
      }
      if (row.packet.size()) row.trace(rays, visibility, out);
      traced += row.traced;
    });
  }
  return traced;
}

void CpuDirectLight::render(const Light& light, Image& out) { render_counting_rays(light, out); }

}  // namespace relight
