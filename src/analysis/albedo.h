// Albedo = photo / illumination (thesis 2.4.2), per pixel, with the pixels
// where the illumination is too small to divide by (deep shadow, grazing
// light), the geometry covers too little of the pixel, the photo clipped, or
// the albedo would be brighter than a surface can be filled from reliable
// neighbours on the same surface.
#pragma once

#include "core/image.h"
#include "render/gbuffer.h"
#include "render/render_illumination.h"

namespace relight {

// The albedo of one triangle of the scene mesh.
struct TriangleAlbedo {
  uint32_t triangle;
  Vec3 albedo;
};

struct AlbedoImages {
  Image albedo;                      // per pixel, the surface's own albedo (not coverage-weighted)
  Image albedo_coverage;             // albedo x coverage: 0 on the background, like albedo_gt.exr
  Vec3 mean = Vec3::Constant(0.5f);  // mean over reliable pixels; the default for unseen surfaces
  size_t filled = 0;                 // pixels filled from neighbours or the mean
  // The pixels whose photo / illumination came out brighter than a surface
  // can be (above bright_bound: the illumination is wrong there), filled in
  // `albedo`; here their index and that photo / illumination (capped at 10),
  // for re-lighting: the model's light is wrong there by a factor (a side face
  // the photo does not show, a facet's own shadow), and the new light,
  // rendered through the same model, is taken as wrong by the same factor.
  // The unchanged rig then gives the photo back, and a new one changes it by
  // the ratio of new to old light (photo_layers).
  std::vector<std::pair<uint32_t, Vec3>> as_divided;
  float bright_bound = 1.0f;
  // 1 per pixel near an edge of the illumination that the photo shows a few
  // pixels away (IlluminationAlignment; with align_edges, the illumination
  // divided by there was moved onto the photo's edges); empty: not looked for.
  std::vector<uint8_t> edge_mismatch;
  float edge_offset_px = 0.0f;  // how far the photo's edges lie from the illumination's, at most

  // Triangles the camera does not see, or shows by too few whole pixels
  // (kFewPixels), whose albedo a probe shows (their radiance in the probe
  // over their illumination): for the light bounced off them in later renders.
  std::vector<TriangleAlbedo> unseen_triangles;
};

// `clipped` (empty, or 1 per pixel of the photo) marks the pixels of an LDR
// photo that clipped: like those in deep shadow, they are filled from their
// surface (Scene::photo_clipped).
AlbedoImages recover_albedo(const Image& photo, const std::vector<uint8_t>& clipped,
                            const IlluminationImages& illumination, const GBuffer& gbuffer);

// The albedo with the photo's blur of sigma_px (photo_blur.h) undone: the
// photo is blur(c a L) + blur((1 - c) B), so where the light is even over the
// blur's reach the division gives a = blur(c a) / blur(c); blur(c a) is
// deconvolved (deblur) and divided by the pixel's own coverage where it is
// at least kMinCoverage, the rest left as it was. Kept within 0 and the
// albedo's bright bound. Done band_rows rows at a time (0: about
// kSharpenBandPixels' worth; at least the deconvolution's reach), the same
// to a thousandth whatever the bands.
void sharpen_albedo(AlbedoImages& albedo, const GBuffer& gbuffer, float sigma_px, int band_rows = 0);
inline constexpr int64_t kSharpenBandPixels = 1 << 20;

}  // namespace relight
