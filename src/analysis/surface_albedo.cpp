#include "analysis/surface_albedo.h"

#include <algorithm>
#include <cmath>

namespace relight {

namespace {
Vec3 clamp01(const Vec3& v) { return v.cwiseMax(0.0f).cwiseMin(1.0f); }
}  // namespace

PhotoAlbedo::PhotoAlbedo(const Camera& camera, const GBuffer& gbuffer, const Image& albedo, const Vec3& unseen,
                         std::span<const TriangleAlbedo> unseen_triangles)
    : camera_(camera), gbuffer_(gbuffer), albedo_(albedo) {
  size_t triangles = 0;
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const auto s = gbuffer.central(x, y); s.hit) triangles = std::max<size_t>(triangles, s.surface.prim + 1);
  for (const TriangleAlbedo& t : unseen_triangles) triangles = std::max<size_t>(triangles, t.triangle + 1);
  std::vector<Vec3> sum(triangles, Vec3::Zero());
  std::vector<int> count(triangles, 0);
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const auto s = gbuffer.central(x, y); s.hit) {
        sum[s.surface.prim] += clamp01(albedo.at(x, y));
        ++count[s.surface.prim];
      }
  triangle_mean_.resize(triangles);
  for (size_t t = 0; t < triangles; ++t)
    triangle_mean_[t] = count[t] ? Vec3(sum[t] / float(count[t])) : clamp01(unseen);
  for (const TriangleAlbedo& t : unseen_triangles)
    if (!count[t.triangle]) triangle_mean_[t.triangle] = clamp01(t.albedo);
  triangle_mean_.push_back(clamp01(unseen));  // the last entry: any triangle beyond those seen
}

std::vector<uint8_t> triangles_in_view(const GBuffer& gbuffer, size_t triangles) {
  std::vector<uint8_t> seen(triangles, 0);
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const auto s = gbuffer.central(x, y); s.hit && s.surface.prim < triangles) seen[s.surface.prim] = 1;
  return seen;
}

Vec3 PhotoAlbedo::at(const SurfacePoint& p) const {
  if (const auto pixel = gbuffer_.pixel_showing(camera_, p)) return clamp01(albedo_.at(pixel->x, pixel->y));
  return triangle_mean_[std::min<size_t>(p.prim, triangle_mean_.size() - 1)];
}

}  // namespace relight
