// Analysis: works out the light the photo was taken under and removes it.
// Renders the initial illumination under a strategy — by path tracing or by
// radiosity on the mesh refined for the photo
// (analysis/radiosity_illumination.h) — and divides the photo by it. With
// interreflection on, light bounced off what the photo or a probe shows is
// the radiance shown there (analysis/photo_radiance.h; with the path tracer
// and BounceSource::photo), so only surfaces neither shows need an albedo;
// or (BounceSource::albedo) it re-renders with the recovered albedo until it
// settles (thesis 3.7's "iterative approach"). Either way the residual says
// how well albedo x illumination rendered back gives the photo.
#pragma once

#include <filesystem>
#include <functional>
#include <optional>
#include <string>

#include "analysis/albedo.h"
#include "analysis/strategy.h"
#include "analysis/vignetting.h"
#include "core/progress.h"
#include "render/gbuffer.h"
#include "render/radiosity.h"
#include "render/specular.h"
#include "scene/scene.h"

namespace relight {

// How the initial illumination is simulated (thesis 3.2, 3.3).
enum class AnalysisMethod { path, radiosity };
const char* to_string(AnalysisMethod m);
std::optional<AnalysisMethod> parse_analysis_method(const std::string& s);

// Where light bounced off a surface the camera sees comes from: the
// radiance the photo shows there (photo), or the recovered albedo times the
// rendered illumination, iterated to a fixed point (albedo).
enum class BounceSource { photo, albedo };
const char* to_string(BounceSource s);
std::optional<BounceSource> parse_bounce_source(const std::string& s);

struct AnalysisOptions {
  AnalysisMethod method = AnalysisMethod::path;
  Strategy strategy = Strategy::combined;
  int paths_per_pixel = 64;
  int gbuffer_samples = 9;  // sub-pixel samples per pixel (anti-aliasing)
  uint64_t seed = 1;
  int max_bounces = IntegratorOptions::kMaxBounces;
  bool interreflection = true;
  BounceSource bounce_source = BounceSource::photo;  // with interreflection on, --method path
  bool denoise = true;                                // filter the environment + interreflection part of each render
  // The environment and interreflection traced at every this-many-th pixel
  // each way (render_illumination.h); 0: sparse_indirect_stride of the
  // photo, which analyze() puts in its result's options.
  int indirect_stride = 0;
  // A quick analysis made to be replaced (preview_options).
  bool preview = false;
  int max_iterations = 4;                             // interreflection re-renders at most (bounce source albedo)
  float tolerance = 0.005f;                           // stop when the mean albedo change is below this
  // Divide by the illumination with its edges moved onto the photo's
  // (IlluminationAlignment); off: they are only found and reported.
  bool align_edges = false;
  // Analyse through the scene's camera as given; otherwise registered to the
  // photo where it is visibly off (register_when_off, camera_registration.h).
  bool keep_camera = false;
  // Leave the photo's vignetting in it; otherwise one measured against the
  // probes is divided out (photo_vignetting, vignetting.h).
  bool keep_vignetting = false;
  // Undo in the albedo a blur of the photo measured against the render
  // (photo_blur.h; sharpen_albedo, albedo.h). Off by default: a model whose
  // edges differ from the photo's can pass for a soft photo, and sharpening
  // a photo that is not soft costs more than leaving a soft one soft.
  bool sharpen = false;
  // With method radiosity, per node (paths_per_pixel is the path tracer's):
  int node_samples = 64;  // for the light from the lights and the environment
  int gather_rays = 256;  // for the light from the other surfaces
  // With method radiosity: the lights' direct light traced per pixel
  // (paths_per_pixel samples) rather than interpolated from the nodes.
  bool direct_per_pixel = true;
};

// A preview of the analysis `full` would make, in a fraction of its time,
// to show while it runs: an eighth of the paths (at least 4), one sample
// per pixel (no anti-aliasing of edges), the rest as `full`; made of the
// photo reduced to at most kPreviewPixels (reduce_for_preview).
AnalysisOptions preview_options(AnalysisOptions full);
inline constexpr int64_t kPreviewPixels = 1 << 19;
// The scene with its photo (and what is given in its pixels: the clipped
// mask, a grey card's polygon, a chart's corners) reduced to at most
// max_pixels, the camera bound to the smaller photo; a smaller photo is left
// as it is. `why` names the reduction in the log.
void reduce_photo(Scene& scene, int64_t max_pixels, const char* why);
inline void reduce_for_preview(Scene& scene) { reduce_photo(scene, kPreviewPixels, "preview"); }

// The radiosity solver's settings of an analysis.
RadiosityOptions radiosity_options(const AnalysisOptions& options);

// The render settings of an analysis, shared by every later render of it.
IlluminationOptions illumination_options(const AnalysisOptions& options);

struct Analysis {
  AnalysisOptions options;
  IlluminationImages illumination;  // of the last iteration
  AlbedoImages albedo;
  std::vector<float> coverage;  // the mask
  int iterations = 0;           // renders done
  // How far albedo x the illumination rendered back with it (on every
  // surface) is from the photo: sum |difference| / sum photo, over blocks of
  // 8 x 8 pixels that see only geometry.
  float residual = 0.0f;
  // The photo's values per unit of the probes' (probe_exposure.h), where
  // found to differ from 1: the analysis divided photo / this, and the
  // albedo and every re-lit image are in the probes' units (the lights').
  Vec3 photo_exposure = Vec3::Ones();
  // The photo's vignetting where found (vignetting.h): divided out of it
  // before the exposure.
  std::optional<Vignetting> photo_vignetting;
  // How much softer the photo is than the render, where found (a Gaussian's
  // standard deviation, pixels; photo_blur.h): the illumination divided by
  // was blurred alike.
  float photo_blur_px = 0.0f;
  // The camera the analysis saw the scene through where it is not the
  // scene's: registered to the photo (register_when_off). Every render of
  // the analysis takes it.
  std::optional<CameraSpec> registered_camera;
  // Where the scene has glossy surfaces: their highlights under the photo's
  // light (render/specular.h; mean over each pixel's geometry samples),
  // taken off the photo before it was divided, and 1 per pixel where the
  // highlight is most of what the photo shows there (the albedo filled from
  // its surface instead). Empty where every surface is matte.
  Image specular;
  std::vector<uint8_t> highlights;
};

// `photo` brought to the units `analysis` divided it in: its vignetting
// divided out, then its exposure.
void bring_to_analysis_units(Image& photo, const Analysis& analysis);

// The share of a pixel's photo (luminance) above which its highlight makes
// it unreliable: the albedo would be the small difference of two large,
// uncertain values.
inline constexpr float kHighlightShare = 0.5f;

class PhotoRadiance;

// The highlights `gloss` would show under the scene's `lighting`, as the
// photo was taken: a reflected ray that meets a surface the photo (or a
// probe) shows takes the radiance shown there (`photo_radiance`, where
// given), elsewhere a path's light off the mid grey surfaces unseen take
// before any albedo is known. `options`: its bounces. Holds references to
// all but `options`.
class PhotoSpecular {
 public:
  PhotoSpecular(const RayScene& rays, const Lighting& lighting, const SurfaceGloss& gloss,
                const PhotoRadiance* photo_radiance, const AnalysisOptions& options);
  PhotoSpecular(const PhotoSpecular&) = delete;
  PhotoSpecular& operator=(const PhotoSpecular&) = delete;
  const SpecularReflection& reflection() const { return specular_; }

 private:
  UniformAlbedo unseen_;
  Integrator integrator_;
  const PhotoRadiance* photo_radiance_;
  ReflectedRadiance surfaces_;
  SpecularReflection specular_;
};

// PhotoSpecular's highlights in every pixel, at the options' paths and seed.
Image photo_highlights(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const Lighting& lighting,
                       const SurfaceGloss& gloss, const PhotoRadiance* photo_radiance, const AnalysisOptions& options,
                       Progress& progress, const std::string& label = "highlights");

// The camera an analysis with `options` sees `scene` through: registered
// to the photo where it is visibly off and the options allow (the scene's
// camera is then set to it, and it is returned).
std::optional<CameraSpec> camera_for_analysis(Scene& scene, const RayScene& rays, const AnalysisOptions& options,
                                              Progress& progress);

// Renders what the scene's camera sees (the G-buffer) with the options' seed
// and sub-pixel samples: the same for the analysis and every later render.
GBuffer scene_gbuffer(const Scene& scene, const RayScene& rays, const AnalysisOptions& options);

// Called with the albedo each render recovers (render 1: white surfaces,
// then one per interreflection pass), to follow the iteration.
using AlbedoObserver = std::function<void(int render, const AlbedoImages& albedo)>;

Analysis analyze(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const AnalysisOptions& requested,
                 Progress& progress, const AlbedoObserver& on_albedo = {});

}  // namespace relight
