// PhotoAlbedo: the albedo of a surface point that light bounces off, taken
// from the recovered albedo image where the camera sees that point, and a
// default elsewhere (the mean recovered albedo: surfaces the photo does not
// show are assumed to be like those it does).
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
  Vec3 unseen_;
};

}  // namespace relight
