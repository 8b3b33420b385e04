// PhotoAlbedo: the albedo of a surface point that light bounces off, taken
// from the recovered albedo image where the camera sees that point; where it
// does not (behind a column, under a table), the mean albedo the photo shows
// of the same triangle; for a triangle the photo does not show at all, the
// albedo a probe shows it has (where the analysis found one), else a default
// (the mean recovered albedo: unseen surfaces are assumed to be like those
// seen).
#pragma once

#include <span>

#include "analysis/albedo.h"
#include "core/image.h"
#include "render/gbuffer.h"
#include "render/integrator.h"

namespace relight {

class PhotoAlbedo final : public SurfaceAlbedo {
 public:
  // albedo: per pixel, not coverage-weighted; unseen: the default;
  // unseen_triangles: the albedo of triangles no pixel shows, where known.
  PhotoAlbedo(const Camera& camera, const GBuffer& gbuffer, const Image& albedo, const Vec3& unseen,
              std::span<const TriangleAlbedo> unseen_triangles = {});
  Vec3 at(const SurfacePoint& p) const override;

 private:
  const Camera& camera_;
  const GBuffer& gbuffer_;
  const Image& albedo_;
  std::vector<Vec3> triangle_mean_;  // the default where a triangle is unseen
};

// Per triangle of a mesh of `triangles`: 1 where a pixel's centre-most
// sample shows it.
std::vector<uint8_t> triangles_in_view(const GBuffer& gbuffer, size_t triangles);

}  // namespace relight
