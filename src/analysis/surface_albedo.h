// PhotoAlbedo: the albedo of a surface point that light bounces off, taken
// from the recovered albedo image where the camera sees that point; where it
// does not (behind a column, under a table), the mean albedo the photo shows
// of the same triangle over the pixels that show it whole; for a triangle the
// photo shows by fewer than kFewPixels such pixels, the albedo a probe shows
// it has (where the analysis found one), else a default (the mean recovered
// albedo: unseen surfaces are assumed to be like those seen).
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
  // unseen_triangles: the albedo of triangles the photo shows too little of
  // (fewer than kFewPixels whole pixels), where known.
  PhotoAlbedo(const Camera& camera, const GBuffer& gbuffer, const Image& albedo, const Vec3& unseen,
              std::span<const TriangleAlbedo> unseen_triangles = {});
  Vec3 at(const SurfacePoint& p) const override;

 private:
  const Camera& camera_;
  const GBuffer& gbuffer_;
  const Image& albedo_;
  std::vector<Vec3> triangle_mean_;  // the default where a triangle is unseen
};

// Fewer pixels than this showing a triangle whole are too few to take the
// albedo of its unseen part from: a sliver of a wall or ceiling at the frame's
// edge, a few noisy pixels standing for a whole surface that light bounces off.
constexpr uint32_t kFewPixels = 32;

// Per triangle of a mesh of `triangles`: how many pixels show it whole (every
// G-buffer sample on its surface: no silhouette or crease within the pixel,
// whose albedo would mix two surfaces).
std::vector<uint32_t> whole_pixels_per_triangle(const GBuffer& gbuffer, size_t triangles);

}  // namespace relight
