// RelightView: the image the interactive engine shows, at any size — the
// scene's camera re-made for W x H, its G-buffer (the analysis's own at the
// photo's size), one surface per pixel for the fast backends, and the
// analysis's layers (albedo, background) at that size.
#pragma once

#include <memory>

#include "relight/render_rig.h"
#include "render/direct_light.h"

namespace relight {

class RelightView {
 public:
  // width/height 0: the photo's size, where the view is exactly the
  // analysis's (its G-buffer and layers). Other sizes look each surface
  // point's albedo up in the photo (as bounce light does) and the background
  // in the photo or, outside it, in the environment. Holds a reference to
  // the analysed scene's G-buffer at the photo's size. samples_per_pixel:
  // of another size's G-buffer (0: the photo's).
  explicit RelightView(const AnalysedScene& analysed, int width = 0, int height = 0, int samples_per_pixel = 0);

  int width() const { return camera_.width(); }
  int height() const { return camera_.height(); }
  bool is_photo_size() const { return !owned_gbuffer_; }
  const Camera& camera() const { return camera_; }
  const GBuffer& gbuffer() const { return *gbuffer_; }
  const PixelSurfaces& surfaces() const { return surfaces_; }
  const RelitLayers& layers() const { return layers_; }
  // Each pixel's coverage by geometry: the analysis's at the photo's size.
  const std::vector<float>& coverage() const { return *coverage_; }

 private:
  Camera camera_;
  std::unique_ptr<GBuffer> owned_gbuffer_;
  const GBuffer* gbuffer_;
  PixelSurfaces surfaces_;
  RelitLayers layers_;
  const std::vector<float>* coverage_;
};

// Illumination rendered on a coarse view (the environment's preview), spread
// over a view of width x height of the same camera: bilinear, weighted by the
// coarse pixels' coverage so that the background (no illumination) does not
// darken the geometry's edges.
Image upsample_illumination(const Image& coarse, const std::vector<float>& coarse_coverage, int width, int height);

}  // namespace relight
