// PhotoAlbedo: the albedo of a surface point that light bounces off, taken
// from the recovered albedo image where the camera sees that point; where it
// does not (behind a column, under a table), the mean albedo the photo shows
// of the same triangle; for a triangle the photo does not show at all, a
// default (the mean recovered albedo: unseen surfaces are assumed to be like
// those seen).
#pragma once

#include "core/image.h"
#include "render/gbuffer.h"
#include "render/integrator.h"

namespace relight {

class PhotoAlbedo final : public SurfaceAlbedo {
 public:
  // albedo: per pixel, not coverage-weighted; unseen: the default.
  PhotoAlbedo(const Camera& camera, const GBuffer& gbuffer, const Image& albedo, const Vec3& unseen);
  Vec3 at(const SurfacePoint& p) const override;

 private:
  const Camera& camera_;
  const GBuffer& gbuffer_;
  const Image& albedo_;
  std::vector<Vec3> triangle_mean_;  // the default where a triangle is unseen

};

}  // namespace relight
