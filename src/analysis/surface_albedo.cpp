#include "analysis/surface_albedo.h"

#include <algorithm>
#include <cmath>

namespace relight {

namespace {
Vec3 clamp01(const Vec3& v) { return v.cwiseMax(0.0f).cwiseMin(1.0f); }
}  // namespace

PhotoAlbedo::PhotoAlbedo(const Camera& camera, const GBuffer& gbuffer, const Image& albedo, const Vec3& unseen)
    : camera_(camera), gbuffer_(gbuffer), albedo_(albedo) {
  size_t triangles = 0;
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const auto& s = gbuffer.central(x, y); s.hit) triangles = std::max<size_t>(triangles, s.surface.prim + 1);
  std::vector<Vec3> sum(triangles, Vec3::Zero());
  std::vector<int> count(triangles, 0);
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x)
      if (const auto& s = gbuffer.central(x, y); s.hit) {
        sum[s.surface.prim] += clamp01(albedo.at(x, y));
        ++count[s.surface.prim];
      }
  triangle_mean_.resize(triangles);
  for (size_t t = 0; t < triangles; ++t) triangle_mean_[t] = count[t] ? Vec3(sum[t] / float(count[t])) : clamp01(unseen);
  triangle_mean_.push_back(clamp01(unseen));  // the last entry: any triangle beyond those seen
}

Vec3 PhotoAlbedo::at(const SurfacePoint& p) const {
  const Vec3& unseen = triangle_mean_[std::min<size_t>(p.prim, triangle_mean_.size() - 1)];
  const auto pos = camera_.project(p.position);
  if (!pos) return unseen;
  const int x = int(std::floor(pos->x())), y = int(std::floor(pos->y()));
  if (x < 0 || y < 0 || x >= albedo_.width || y >= albedo_.height) return unseen;
  const GBufferSample& s = gbuffer_.central(x, y);
  if (!s.hit) return unseen;
  // The pixel shows this point if it sees the same triangle or a surface at
  // the same distance (a neighbouring triangle of the same surface).
  const float dist = (p.position - camera_.position()).norm();
  if (s.surface.prim != p.prim && std::abs(s.surface.distance - dist) > 0.01f * dist) return unseen;
  return clamp01(albedo_.at(x, y));
}

}  // namespace relight
