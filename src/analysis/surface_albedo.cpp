#include "analysis/surface_albedo.h"

#include <cmath>

namespace relight {

PhotoAlbedo::PhotoAlbedo(const Camera& camera, const GBuffer& gbuffer, const Image& albedo, const Vec3& unseen)
    : camera_(camera), gbuffer_(gbuffer), albedo_(albedo), unseen_(unseen.cwiseMax(0.0f).cwiseMin(1.0f)) {}

Vec3 PhotoAlbedo::at(const SurfacePoint& p) const {
  const auto pos = camera_.project(p.position);
  if (!pos) return unseen_;
  const int x = int(std::floor(pos->x())), y = int(std::floor(pos->y()));
  if (x < 0 || y < 0 || x >= albedo_.width || y >= albedo_.height) return unseen_;
  const GBufferSample& s = gbuffer_.central(x, y);
  if (!s.hit) return unseen_;
  // The pixel shows this point if it sees the same triangle or a surface at
  // the same distance (a neighbouring triangle of the same surface).
  const float dist = (p.position - camera_.position()).norm();
  if (s.surface.prim != p.prim && std::abs(s.surface.distance - dist) > 0.01f * dist) return unseen_;
  return albedo_.at(x, y).cwiseMax(0.0f).cwiseMin(1.0f);
}

}  // namespace relight
