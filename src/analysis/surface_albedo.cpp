#include "analysis/surface_albedo.h"

#include <algorithm>
#include <cmath>
#include <optional>

namespace relight {

namespace {
Vec3 clamp01(const Vec3& v) { return v.cwiseMax(0.0f).cwiseMin(1.0f); }

// The triangle pixel (x, y) shows whole (see whole_pixels_per_triangle).
std::optional<uint32_t> whole_pixel_triangle(const GBuffer& gbuffer, int x, int y) {
  if (const auto t = gbuffer.single_triangle(x, y)) return t;  // nearly every pixel: no sample recomputed
  if (!gbuffer.one_surface(x, y)) return std::nullopt;
  return gbuffer.central(x, y).surface.prim;
}
}  // namespace

PhotoAlbedo::PhotoAlbedo(const Camera& camera, const GBuffer& gbuffer, const Image& albedo, const Vec3& unseen,
                         std::span<const TriangleAlbedo> unseen_triangles)
    : camera_(camera), gbuffer_(gbuffer), albedo_(albedo) {
  // Sized by the triangles seen whole or listed: any other takes the last
  // entry, the default.
  std::vector<Vec3> sum;
  std::vector<uint32_t> count;
  const auto reach = [&](uint32_t t) {
    if (t < sum.size()) return;
    sum.resize(t + 1, Vec3::Zero());
    count.resize(t + 1, 0);
  };
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const auto t = whole_pixel_triangle(gbuffer, x, y)) {
        reach(*t);
        sum[*t] += clamp01(albedo.at(x, y));
        ++count[*t];
      }
  for (const TriangleAlbedo& t : unseen_triangles) reach(t.triangle);
  const size_t triangles = sum.size();
  triangle_mean_.resize(triangles);
  for (size_t t = 0; t < triangles; ++t)
    triangle_mean_[t] = count[t] ? Vec3(sum[t] / float(count[t])) : clamp01(unseen);
  for (const TriangleAlbedo& t : unseen_triangles)
    if (count[t.triangle] < kFewPixels) triangle_mean_[t.triangle] = clamp01(t.albedo);
  triangle_mean_.push_back(clamp01(unseen));  // the last entry: any triangle beyond those seen
}

std::vector<uint32_t> whole_pixels_per_triangle(const GBuffer& gbuffer, size_t triangles) {
  std::vector<uint32_t> count(triangles, 0);
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const auto t = whole_pixel_triangle(gbuffer, x, y); t && *t < triangles) ++count[*t];
  return count;
}

Vec3 PhotoAlbedo::at(const SurfacePoint& p) const {
  if (const auto pixel = gbuffer_.pixel_showing(camera_, p)) return clamp01(albedo_.at(pixel->x, pixel->y));
  return triangle_mean_[std::min<size_t>(p.prim, triangle_mean_.size() - 1)];
}

}  // namespace relight
