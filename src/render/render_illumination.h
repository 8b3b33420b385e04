// Renders the illumination of every pixel of a G-buffer: the mean, over the
// pixel's samples that see geometry, of the light a white diffuse surface
// there would reflect; and the mean environment radiance over those that see
// the background. Multithreaded, deterministic for a seed.
//
// The two parts of the light are rendered at different densities. The
// lights' direct light, with its sharp shadows, is traced at every pixel.
// The rest — the environment and all interreflection — is smooth almost
// everywhere: it is traced at every `indirect_stride`-th pixel each way,
// denoised there, and interpolated between them along the surfaces (a
// pixel takes only the traced pixels that lie on its own surface, each of
// its sub-pixel samples apart where it holds an edge); a pixel with none on
// its surface (a thin pole between them) traces its own.
#pragma once

#include "core/image.h"
#include "core/progress.h"
#include "render/denoise.h"
#include "render/gbuffer.h"
#include "render/integrator.h"

namespace relight {

struct IlluminationImages {
  Image surface;     // mean illumination over the geometry samples (0 where none)
  Image background;  // mean environment radiance over the background samples (0 where none)
};

struct IlluminationOptions {
  int paths_per_pixel = 64;  // spread evenly over the pixel's G-buffer samples
  uint64_t seed = 1;
  bool denoise = true;       // filter the environment + interreflection part
  // The environment and interreflection traced at every this-many-th pixel
  // each way (1: every pixel; 0: sparse_indirect_stride of the image).
  int indirect_stride = 0;
};

// The stride for a width x height image: about kSparseIndirectPixels traced
// (every pixel of a smaller one).
inline constexpr int64_t kSparseIndirectPixels = 1 << 19;
int sparse_indirect_stride(int width, int height);
// The stride a width x height render with `options` traces at: theirs, or
// sparse_indirect_stride's.
int indirect_stride(const IlluminationOptions& options, int width, int height);

// The direct light's samples per pixel: paths_per_pixel up to
// kDirectSampledPixels pixels, fewer beyond, so that a larger image takes
// no more samples in all — down to one per sub-pixel sample (a shadow's edge
// is still anti-aliased; a soft shadow's noise is left to the denoiser).
inline constexpr int64_t kDirectSampledPixels = 1 << 20;
int direct_samples_per_pixel(int paths_per_pixel, const GBuffer& gbuffer);

// A synthetic photo: each camera sample's illumination times the albedo of
// the surface it sees, the environment where it sees none; no denoising.
// Used to make scenes with a known albedo (the example, round-trip tests).
Image synthesize_photo(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                       const SurfaceAlbedo& albedo, int paths_per_pixel, uint64_t seed, Progress& progress);

// The mean number of surfaces a path of `integrator` meets after the one it
// starts from (the vertices bounce_vertices keeps), over one path from each
// of about `paths` pixels spread evenly over the view: a render's cost per
// path. It follows what the renderer knows (a path ends where it meets known
// radiance) and the room (in a closed one, with bright walls, a path
// bounces on many times; under an open sky it leaves). Deterministic for a
// seed; 0 where the view holds no geometry.
double mean_path_vertices(const GBuffer& gbuffer, const Integrator& integrator, int paths, uint64_t seed);

// The mean environment radiance over each pixel's samples that see the
// background (0 where none does): IlluminationImages::background.
Image render_background(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator);

// The illumination over the geometry in its two parts, each denoised as
// render_illumination does: the light straight from the lights, and the rest
// (the environment and all interreflection). render_illumination's surface
// is their sum.
struct IlluminationParts {
  Image direct, indirect;
  Image total() const;  // direct + indirect
};
IlluminationParts render_illumination_parts(const GBuffer& gbuffer, const Integrator& integrator,
                                            const IlluminationOptions& options, Progress& progress,
                                            const std::string& label = "illumination");

// The bounce light of one light after another seen from the same pixels (a
// frame sequence's moving light). A path from the camera does not depend on
// the lights, only where its vertices' shadow rays go: the paths a render
// with `options` traces are traced once, with `paths`' albedo and bounces,
// and kept; each light then costs a shadow ray a vertex
// (render_indirect_part's `kept`), the same light in expectation. 52 bytes
// a vertex: 591 MB for the 77 000 pixels the studio's 640 x 480 view traces
// at stride 2, 64 paths each. Paths in a closed room of bright walls are
// long; where they would take more than `budget_bytes` in all, the tracing
// stops there and within_budget() is false (the caller traces each light's
// own paths instead).
class KeptPaths {
 public:
  static constexpr size_t kDefaultBudget = size_t(2) << 30;
  KeptPaths(const GBuffer& gbuffer, const Integrator& paths, const IlluminationOptions& options, Progress& progress,
            size_t budget_bytes = kDefaultBudget);
  bool within_budget() const { return within_budget_; }
  int stride() const { return stride_; }
  uint64_t seed() const { return seed_; }
  size_t bytes() const;
  // The light `lights` sends along the paths of traced pixel `pixel` (row by
  // row over the traced pixels), and the variance of that mean's luminance.
  Vec3 light(size_t pixel, const Integrator& lights, float& variance) const;

 private:
  // A row of traced pixels' paths (kept by row: no copy joins them).
  struct Row {
    std::vector<Integrator::PathVertex> vertices;
    std::vector<uint32_t> path_end;   // each path's: one past its last vertex
    std::vector<uint32_t> pixel_end;  // each traced pixel's: one past its last path
    size_t bytes() const;
  };
  int stride_, width_ = 0;
  uint64_t seed_;
  bool within_budget_ = true;
  std::vector<Row> rows_;
};

// The two parts alone. The direct part depends only on the lights (not on
// the albedo light bounces off): an analysis renders it once. With `kept`,
// the indirect part is the lights' light along those paths (their pixels,
// stride and seed must be this render's).
Image render_direct_part(const GBuffer& gbuffer, const Integrator& integrator, const IlluminationOptions& options,
                         Progress& progress, const std::string& label = "direct light");
Image render_indirect_part(const GBuffer& gbuffer, const Integrator& integrator, const IlluminationOptions& options,
                           Progress& progress, const std::string& label = "illumination",
                           const KeptPaths* kept = nullptr);

// direct, where given, is render_direct_part's image of these lights and
// options, rendered before.
IlluminationImages render_illumination(const GBuffer& gbuffer, const Camera& camera, const Integrator& integrator,
                                       const IlluminationOptions& options, Progress& progress,
                                       const std::string& label = "illumination", const Image* direct = nullptr,
                                       const KeptPaths* kept = nullptr);

}  // namespace relight
