// The albedo of a shot, one per surface. A shot is many photos of one scene
// from a moving camera; analysed frame by frame, each frame's albedo carries
// its own photo's noise and its own misfits, and a surface's albedo would
// change from frame to frame: the re-lit shot would flicker. The atlas holds
// one albedo per surface point instead: each triangle a square grid of
// texels over its barycentric coordinates (the half with b1 + b2 <= 1 used),
// each no larger than the frames' pixels show of the surface, and each
// texel the weighted mean of every frame's albedo at the pixels that see it.
// Each frame then takes its albedo from the atlas.
#pragma once

#include <cstdint>
#include <span>
#include <utility>
#include <vector>

#include "analysis/analyze.h"
#include "core/image.h"
#include "render/gbuffer.h"
#include "scene/triangle_mesh.h"

namespace relight {

class AlbedoAtlas {
 public:
  // The mesh must outlive the atlas.
  explicit AlbedoAtlas(const TriangleMesh& mesh);

  // First every frame's view (each pixel's centre-most surface point) and
  // camera: each triangle's texels are made as small as the smallest patch
  // of it a pixel of any frame covers.
  void size_for(const PixelSurfaces& view, const Camera& camera);
  // Then each frame's albedo (per pixel, not coverage-weighted) with each
  // pixel's weight (albedo_weights).
  void add(const PixelSurfaces& view, const Image& albedo, std::span<const float> weight);
  // A frame's albedo from the atlas: each pixel its texel's, where a frame
  // gave that texel weight; elsewhere `own`'s pixel.
  Image albedo_for(const PixelSurfaces& view, const Image& own) const;

  size_t texels() const { return sum_.size(); }

 private:
  // The texel of a surface point; -1 where its triangle has no grid.
  int64_t texel_of(const SurfacePoint& point) const;

  const TriangleMesh& mesh_;
  std::vector<uint16_t> side_;   // grid side per triangle, texels (0: no frame shows it)
  std::vector<uint32_t> first_;  // its first texel
  std::vector<Vec3> sum_;        // weighted sum of the albedo, per texel
  std::vector<float> weight_;    // sum of the weights
};

// Pixel pairs (a's, b's) that show the same surface point in two frames:
// b's point projected into a, where a's pixel there sees the same triangle
// within 1 cm.
std::vector<std::pair<size_t, size_t>> shared_points(const PixelSurfaces& a, const Camera& a_camera,
                                                     const PixelSurfaces& b);
// How much an image sequence changes from frame a to frame b where they show
// the same surface: the mean |a - b| over the pairs, relative to a's mean
// there (0 without pairs). Of a fused albedo, its flicker.
double change_at_shared_points(const Image& a, const Image& b, const std::vector<std::pair<size_t, size_t>>& pairs);

// How far each pixel's albedo is trusted, for the atlas: the illumination
// squared (the albedo's noise is the photo's over the illumination) times the
// pixel's coverage squared (an edge pixel mixes the background in); 0 where
// the analysis found the illumination's edge off the photo's (edge_mismatch).
std::vector<float> albedo_weights(const Analysis& analysis);

}  // namespace relight
