// GBuffer: what each pixel of the photo sees. Like a camera's pixel it
// integrates over its area: each pixel holds a fixed number of sub-pixel
// samples (stratified, jittered), each a surface point or the background.
//
// Compact: a pixel whose samples all see one triangle (nearly all of a
// camera-sized photo's) keeps only that triangle, and its samples are
// recomputed from their rays when asked for; only pixels that hold an edge
// (another triangle, the background) keep theirs. About 16 bytes a pixel
// plus 470 per edge pixel, against 470 for every pixel kept whole.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "render/ray_scene.h"
#include "scene/camera.h"

namespace relight {

struct GBufferSample {
  SurfacePoint surface;  // valid when hit
  bool hit = false;
};

class GBuffer {
 public:
  // Traces samples_per_pixel camera rays per pixel (rounded to a square
  // grid). Throws InputError(scene_file, "/camera", ...) when the camera sees
  // no geometry at all. Keeps a reference to `scene` (it recomputes samples
  // on it): the scene must outlive the G-buffer.
  GBuffer(const Camera& camera, const RayScene& scene, int samples_per_pixel, uint64_t seed,
          const std::string& scene_file);

  int width() const { return width_; }
  int height() const { return height_; }
  int samples_per_pixel() const { return spp_; }
  GBufferSample sample(int x, int y, int k) const;
  // All of the pixel's samples at once (out sized samples_per_pixel()).
  void pixel_samples(int x, int y, std::vector<GBufferSample>& out) const;
  // The sub-pixel image position of sample k of pixel (x, y), and its ray.
  Vec2 sample_position(int x, int y, int k) const;
  // Fraction of the pixel's samples that see geometry.
  float coverage(int x, int y) const { return coverage_[size_t(y) * width_ + x]; }
  const std::vector<float>& coverage() const { return coverage_; }
  // The surface seen through the centre-most sample (for per-pixel lookups).
  GBufferSample central(int x, int y) const { return sample(x, y, central_); }
  // Whether two pixels see the same surface: the same triangle, or a similar
  // normal (within ~25 degrees) at a similar depth (within 3 %).
  bool same_surface(int x, int y, int nx, int ny) const;
  // The same test on two surface points (both hit).
  static bool same_surface(const SurfacePoint& a, const SurfacePoint& b);
  // Whether an edge of the geometry lies between two samples: they see
  // different surfaces, or one sees geometry and the other none.
  static bool edge_between(const GBufferSample& a, const GBufferSample& b) {
    return a.hit != b.hit || (a.hit && !same_surface(a.surface, b.surface));
  }

  // Whether every sample of the pixel sees the surface its centre-most
  // sample sees (no silhouette, crease or background within it).
  bool one_surface(int x, int y) const;
  // The triangle every sample of the pixel sees, where all see one (nearly
  // every pixel): known without recomputing a sample.
  std::optional<uint32_t> single_triangle(int x, int y) const {
    const uint32_t slot = slot_[size_t(y) * width_ + x];
    if (slot == kSeesNothing || (slot & kKept)) return std::nullopt;
    return slot;
  }
  // Bytes held per pixel (docs/benchmarks.md, "Memory").
  double bytes_per_pixel() const;

  struct Pixel {
    int x, y;
  };
  // The pixel that shows p, a point reached by a ray from elsewhere (its
  // normals turned towards that ray): p projects into the pixel, the camera
  // is on the side p was reached from, and the pixel's centre-most sample is
  // on p's triangle or at p's distance (within 1 %: not hidden behind
  // something nearer). `camera` is the one the G-buffer was made with.
  std::optional<Pixel> pixel_showing(const Camera& camera, const SurfacePoint& p) const;

 private:
  GBufferSample recomputed(int x, int y, int k, uint32_t prim) const;

  Camera camera_;
  const RayScene* scene_;
  int width_, height_, spp_, grid_, central_;
  uint64_t seed_;
  // Per pixel: the triangle all its samples see; or kKept | the index of
  // its samples in kept_ (divided by spp_); or kSeesNothing.
  std::vector<uint32_t> slot_;
  static constexpr uint32_t kKept = 0x80000000u, kSeesNothing = 0x7fffffffu;
  std::vector<GBufferSample> kept_;
  std::vector<float> coverage_;
  // The centre-most sample's triangle and distance, kept apart: pixel_showing
  // reads them at random pixels for every bounce of every path, and the
  // samples' 9 x 48 bytes per pixel miss the caches.
  struct CentralDepth {
    uint32_t prim;  // kNoPrim where the sample sees no geometry
    float distance;
  };
  static constexpr uint32_t kNoPrim = 0xffffffffu;
  std::vector<CentralDepth> central_depth_;
};

// The surface each pixel sees through its central G-buffer sample, packed
// row by row (the interactive view's one-sample-per-pixel G-buffer; the
// pixels a sparse render traces, render_illumination.h).
struct PixelSurfaces {
  int width = 0, height = 0;
  std::vector<SurfacePoint> surface;  // valid where hit
  std::vector<uint8_t> hit;

  static PixelSurfaces central_samples(const GBuffer& gbuffer);
  // Rows [first_row, end_row) alone.
  static PixelSurfaces central_samples(const GBuffer& gbuffer, int first_row, int end_row);
};

}  // namespace relight
