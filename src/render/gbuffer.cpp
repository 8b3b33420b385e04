#include "render/gbuffer.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "core/error.h"
#include "core/sampling.h"

namespace relight {

GBuffer::GBuffer(const Camera& camera, const RayScene& scene, int samples_per_pixel, uint64_t seed,
                 const std::string& scene_file)
    : width_(camera.width()), height_(camera.height()), seed_(seed) {
  grid_ = std::max(1, int(std::lround(std::sqrt(double(std::max(1, samples_per_pixel))))));
  spp_ = grid_ * grid_;
  central_ = (grid_ / 2) * grid_ + grid_ / 2;
  samples_.resize(size_t(width_) * height_ * spp_);
  coverage_.assign(size_t(width_) * height_, 0.0f);

  tbb::parallel_for(0, height_, [&](int y) {
    for (int x = 0; x < width_; ++x) {
      int hits = 0;
      for (int k = 0; k < spp_; ++k) {
        GBufferSample& s = samples_[(size_t(y) * width_ + x) * spp_ + k];
        const Vec2 pos = sample_position(x, y, k);
        s.hit = scene.intersect(camera.position(), camera.ray_direction(pos.x(), pos.y()), s.surface);
        hits += s.hit;
      }
      coverage_[size_t(y) * width_ + x] = float(hits) / float(spp_);
    }
  });
  central_depth_.resize(coverage_.size());
  for (int y = 0; y < height_; ++y)
    for (int x = 0; x < width_; ++x) {
      const GBufferSample& c = central(x, y);
      central_depth_[size_t(y) * width_ + x] = {c.hit ? c.surface.prim : kNoPrim, c.surface.distance};
    }
  bool any = false;
  for (float c : coverage_) any |= c > 0.0f;
  if (!any)
    throw InputError(scene_file, "/camera", "the camera sees no geometry: check position, look_at and the mesh");
}

bool GBuffer::same_surface(int x, int y, int nx, int ny) const {
  const GBufferSample& a = central(x, y);
  const GBufferSample& b = central(nx, ny);
  return a.hit && b.hit && same_surface(a.surface, b.surface);
}

bool GBuffer::same_surface(const SurfacePoint& a, const SurfacePoint& b) {
  if (a.prim == b.prim) return true;
  return a.geometric_normal.dot(b.geometric_normal) > 0.9f && std::abs(a.distance - b.distance) < 0.03f * a.distance;
}

bool GBuffer::one_surface(int x, int y) const {
  const GBufferSample& c = central(x, y);
  if (!c.hit) return false;
  for (int k = 0; k < spp_; ++k) {
    const GBufferSample& s = sample(x, y, k);
    if (!s.hit || !same_surface(c.surface, s.surface)) return false;
  }
  return true;
}

std::optional<GBuffer::Pixel> GBuffer::pixel_showing(const Camera& camera, const SurfacePoint& p) const {
  const Vec3 to_camera = camera.position() - p.position;
  if (to_camera.dot(p.geometric_normal) <= 0.0f) return std::nullopt;  // reached from the side the camera is not on
  const auto pos = camera.project(p.position);
  if (!pos) return std::nullopt;
  const int x = int(std::floor(pos->x())), y = int(std::floor(pos->y()));
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return std::nullopt;
  const CentralDepth& c = central_depth_[size_t(y) * width_ + x];
  if (c.prim == kNoPrim) return std::nullopt;
  const float dist = to_camera.norm();
  if (c.prim != p.prim && std::abs(c.distance - dist) > 0.01f * dist) return std::nullopt;
  return Pixel{x, y};
}

Vec2 GBuffer::sample_position(int x, int y, int k) const {
  // Jittered grid: one sample in each cell of a grid x grid stratification.
  Rng rng(seed_ ^ 0x6b75ull, size_t(y) * width_ + x, uint64_t(k));
  const int gx = k % grid_, gy = k / grid_;
  const Vec2 j = (grid_ == 1) ? Vec2(0.5f, 0.5f) : rng.uniform2();
  return {x + (gx + j.x()) / grid_, y + (gy + j.y()) / grid_};
}

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

}  // namespace relight
