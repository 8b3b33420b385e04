#include "render/gbuffer.h"

#include <tbb/parallel_for.h>

#include <cmath>

#include "core/error.h"
#include "core/sampling.h"

namespace relight {

GBuffer::GBuffer(const Camera& camera, const RayScene& scene, int samples_per_pixel, uint64_t seed,
                 const std::string& scene_file)
    : camera_(camera), scene_(&scene), width_(camera.width()), height_(camera.height()), seed_(seed) {
  grid_ = std::max(1, int(std::lround(std::sqrt(double(std::max(1, samples_per_pixel))))));
  spp_ = grid_ * grid_;
  central_ = (grid_ / 2) * grid_ + grid_ / 2;
  const size_t pixels = size_t(width_) * height_;
  if (scene.mesh().triangles.size() >= kSeesNothing)
    throw InputError(scene_file, "/geometry", "has more triangles than the G-buffer can number (2^31 - 1)");
  slot_.assign(pixels, kSeesNothing);
  coverage_.assign(pixels, 0.0f);
  central_depth_.assign(pixels, {kNoPrim, 0.0f});

  // Each row's edge pixels' samples, gathered into kept_ once all are traced.
  std::vector<std::vector<GBufferSample>> kept_rows(static_cast<size_t>(height_));
  tbb::parallel_for(0, height_, [&](int y) {
    std::vector<GBufferSample> samples(static_cast<size_t>(spp_));
    for (int x = 0; x < width_; ++x) {
      int hits = 0;
      bool one_triangle = true;
      for (int k = 0; k < spp_; ++k) {
        GBufferSample& s = samples[size_t(k)];
        const Vec2 pos = sample_position(x, y, k);
        s.hit = scene.intersect(camera.position(), camera.ray_direction(pos.x(), pos.y()), s.surface);
        hits += s.hit;
        one_triangle &= s.hit && s.surface.prim == samples[0].surface.prim;
      }
      const size_t i = size_t(y) * width_ + x;
      coverage_[i] = float(hits) / float(spp_);
      const GBufferSample& c = samples[size_t(central_)];
      if (c.hit) central_depth_[i] = {c.surface.prim, c.surface.distance};
      if (one_triangle) {
        slot_[i] = samples[0].surface.prim;
      } else if (hits) {
        slot_[i] = kKept | uint32_t(kept_rows[size_t(y)].size() / size_t(spp_));  // within the row, for now
        kept_rows[size_t(y)].insert(kept_rows[size_t(y)].end(), samples.begin(), samples.end());
      }
    }
  });
  size_t kept_pixels = 0;
  for (int y = 0; y < height_; ++y) {
    for (int x = 0; x < width_; ++x) {
      uint32_t& slot = slot_[size_t(y) * width_ + x];
      if (slot != kSeesNothing && (slot & kKept)) {
        const size_t index = kept_pixels + (slot & ~kKept);
        if (index >= kKept)
          throw InputError(scene_file, "/camera", "the photo holds more edge pixels than the G-buffer can number");
        slot = kKept | uint32_t(index);
      }
    }
    kept_pixels += kept_rows[size_t(y)].size() / size_t(spp_);
  }
  kept_.reserve(kept_pixels * size_t(spp_));
  for (auto& row : kept_rows) {
    kept_.insert(kept_.end(), row.begin(), row.end());
    std::vector<GBufferSample>().swap(row);
  }
  bool any = false;
  for (float c : coverage_) any |= c > 0.0f;
  if (!any)
    throw InputError(scene_file, "/camera", "the camera sees no geometry: check position, look_at and the mesh");
}

GBufferSample GBuffer::sample(int x, int y, int k) const {
  const uint32_t slot = slot_[size_t(y) * width_ + x];
  if (slot == kSeesNothing) return {};
  if (slot & kKept) return kept_[size_t(slot & ~kKept) * spp_ + k];
  return recomputed(x, y, k, slot);
}

void GBuffer::pixel_samples(int x, int y, std::vector<GBufferSample>& out) const {
  out.resize(size_t(spp_));
  for (int k = 0; k < spp_; ++k) out[size_t(k)] = sample(x, y, k);
}

GBufferSample GBuffer::recomputed(int x, int y, int k, uint32_t prim) const {
  const Vec2 pos = sample_position(x, y, k);
  GBufferSample s;
  s.hit = scene_->intersect_triangle(prim, camera_.position(), camera_.ray_direction(pos.x(), pos.y()), s.surface);
  return s;
}

double GBuffer::bytes_per_pixel() const {
  const double bytes = double(slot_.size()) * sizeof(uint32_t) + double(coverage_.size()) * sizeof(float) +
                       double(central_depth_.size()) * sizeof(CentralDepth) +
                       double(kept_.size()) * sizeof(GBufferSample);
  return bytes / double(slot_.size());
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
  const uint32_t slot = slot_[size_t(y) * width_ + x];
  if (slot == kSeesNothing) return false;
  if (!(slot & kKept)) return true;  // one triangle
  const GBufferSample c = central(x, y);
  if (!c.hit) return false;
  for (int k = 0; k < spp_; ++k) {
    const GBufferSample s = sample(x, y, k);
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
  return central_samples(gbuffer, 0, gbuffer.height());
}

PixelSurfaces PixelSurfaces::central_samples(const GBuffer& gbuffer, int first_row, int end_row) {
  PixelSurfaces s;
  s.width = gbuffer.width();
  s.height = end_row - first_row;
  s.surface.resize(size_t(s.width) * s.height);
  s.hit.resize(s.surface.size());
  for (int y = 0; y < s.height; ++y)
    for (int x = 0; x < s.width; ++x) {
      const GBufferSample& g = gbuffer.central(x, first_row + y);
      const size_t i = size_t(y) * s.width + x;
      s.surface[i] = g.surface;
      s.hit[i] = g.hit;
    }
  return s;
}

}  // namespace relight
