#include "analysis/analyze.h"

#include <spdlog/spdlog.h>

#include "analysis/camera_registration.h"
#include "analysis/illumination_alignment.h"
#include "analysis/photo_blur.h"
#include "analysis/photo_radiance.h"
#include "analysis/photo_units.h"
#include "analysis/probe_exposure.h"
#include "analysis/radiosity_illumination.h"
#include "analysis/surface_albedo.h"
#include "analysis/vignetting.h"
#include "core/error.h"
#include "io/image_io.h"
#include "render/specular.h"

namespace relight {

namespace fs = std::filesystem;

std::optional<CameraSpec> camera_for_analysis(Scene& scene, const RayScene& rays, const AnalysisOptions& options,
                                              Progress& progress) {
  if (options.keep_camera) return std::nullopt;
  return register_when_off(scene, rays, progress);
}

GBuffer scene_gbuffer(const Scene& scene, const RayScene& rays, const AnalysisOptions& options) {
  return GBuffer(scene.camera, rays, options.gbuffer_samples, options.seed, scene.path.string());
}

const char* to_string(AnalysisMethod m) { return m == AnalysisMethod::radiosity ? "radiosity" : "path"; }

std::optional<AnalysisMethod> parse_analysis_method(const std::string& s) {
  if (s == "path") return AnalysisMethod::path;
  if (s == "radiosity") return AnalysisMethod::radiosity;
  return std::nullopt;
}

const char* to_string(BounceSource s) { return s == BounceSource::photo ? "photo" : "albedo"; }

std::optional<BounceSource> parse_bounce_source(const std::string& s) {
  if (s == "photo") return BounceSource::photo;
  if (s == "albedo") return BounceSource::albedo;
  return std::nullopt;
}

AnalysisOptions preview_options(AnalysisOptions full) {
  constexpr int kPathsDivisor = 8, kLeastPaths = 4;
  full.paths_per_pixel = std::max(std::min(kLeastPaths, full.paths_per_pixel), full.paths_per_pixel / kPathsDivisor);
  full.gbuffer_samples = 1;
  full.preview = true;
  return full;
}

void reduce_photo(Scene& scene, int64_t max_pixels, const char* why) {
  const int w = scene.photo.width, h = scene.photo.height;
  const double scale = std::sqrt(double(max_pixels) / (double(w) * double(h)));
  if (scale >= 1.0) return;
  const int rw = std::max(1, int(std::lround(w * scale))), rh = std::max(1, int(std::lround(h * scale)));
  scene.photo = resized(scene.photo, rw, rh);
  if (!scene.photo_clipped.empty()) {
    // A reduced pixel is clipped where any pixel it covers is.
    Image clipped(w, h);
    for (size_t i = 0; i < clipped.size(); ++i) clipped.pixels[i] = Vec3::Constant(scene.photo_clipped[i]);
    const Image reduced = resized(clipped, rw, rh);
    scene.photo_clipped.assign(reduced.size(), 0);
    for (size_t i = 0; i < reduced.size(); ++i) scene.photo_clipped[i] = reduced.pixels[i].x() > 0.0f;
  }
  const Vec2 to_reduced(float(rw) / float(w), float(rh) / float(h));
  if (scene.reference) {
    for (Vec2& p : scene.reference->polygon) p = p.cwiseProduct(to_reduced);
    for (Vec2& p : scene.reference->colorchecker) p = p.cwiseProduct(to_reduced);
  }
  scene.camera = Camera(scene.camera.spec(), rw, rh);
  spdlog::info("{}: the photo reduced from {}x{} to {}x{}", why, w, h, rw, rh);
}

RadiosityOptions radiosity_options(const AnalysisOptions& options) {
  RadiosityOptions o;
  o.light_samples = options.node_samples;
  o.gather_rays = options.gather_rays;
  o.max_bounces = options.max_bounces;
  o.seed = options.seed;
  return o;
}

IlluminationOptions illumination_options(const AnalysisOptions& options) {
  IlluminationOptions o;
  o.paths_per_pixel = options.paths_per_pixel;
  o.seed = options.seed;
  o.denoise = options.denoise;
  o.indirect_stride = options.indirect_stride;
  return o;
}

namespace {

float mean_abs_change(const Image& a, const Image& b, const std::vector<float>& coverage) {
  double sum = 0.0;
  size_t n = 0;
  for (size_t i = 0; i < a.size(); ++i)
    if (coverage[i] > 0.0f) {
      sum += (a.pixels[i] - b.pixels[i]).cwiseAbs().mean();
      ++n;
    }
  return n ? float(sum / n) : 0.0f;
}

// A camera inside a closed object sees only surfaces no light reaches: the
// photo cannot be divided by their illumination anywhere.
bool no_light_reaches_the_view(const Image& surface_illumination, const std::vector<float>& coverage) {
  for (size_t i = 0; i < coverage.size(); ++i)
    if (coverage[i] > 0.0f && luminance(surface_illumination.pixels[i]) > 0.0f) return false;
  return true;
}

// How far the analysis explains the photo: albedo x the illumination
// rendered back with that albedo on every surface (what rendering the
// scene's own lights gives), against the photo, over the pixels that see
// only geometry. Compared in blocks of kResidualBlock^2 pixels, so that the
// render's noise averages out and what remains is bias: light the analysis
// missed or counted twice. Returns sum |block difference| / sum block photo.
constexpr int kResidualBlock = 8;
constexpr int kResidualPathsDivisor = 4;  // the render back takes paths_per_pixel / this
constexpr float kLargeResidual = 0.05f;   // above: warn
constexpr int kProbeAlbedoPaths = 16;     // per probe pixel, for the albedo of what only a probe shows
// With the photo's radiance, the renders before the closing pass take
// paths_per_pixel / kBouncePathsDivisor paths, but no fewer than kMinBouncePaths.
constexpr int kBouncePathsDivisor = 2;
constexpr int kMinBouncePaths = 32;
constexpr int kPhotoRadiancePasses = 1;   // with the photo's radiance: interreflection passes

float residual_of(const Image& photo, const Image& albedo, const Image& illumination,
                  const std::vector<float>& coverage) {
  const int w = photo.width, h = photo.height;
  double difference = 0.0, total = 0.0;
  for (int by = 0; by < h; by += kResidualBlock)
    for (int bx = 0; bx < w; bx += kResidualBlock) {
      double p = 0.0, r = 0.0;
      for (int y = by; y < std::min(h, by + kResidualBlock); ++y)
        for (int x = bx; x < std::min(w, bx + kResidualBlock); ++x) {
          const size_t i = size_t(y) * w + x;
          if (coverage[i] < 1.0f) continue;
          p += luminance(photo.pixels[i]);
          r += luminance(albedo.pixels[i].cwiseProduct(illumination.pixels[i]));
        }
      difference += std::abs(r - p);
      total += p;
    }
  return total > 0.0 ? float(difference / total) : 0.0f;
}

constexpr float kLargeEdgeOffsetPx = 1.0f;  // above: warn (where IlluminationAlignment moves)

void report_edge_offset(const Scene& scene, const AlbedoImages& albedo, const std::vector<float>& coverage,
                        bool aligned) {
  size_t moved = 0, seen = 0;
  for (size_t i = 0; i < coverage.size(); ++i)
    if (coverage[i] > 0.0f) {
      ++seen;
      moved += i < albedo.edge_mismatch.size() && albedo.edge_mismatch[i];
    }
  const double share = seen ? 100.0 * double(moved) / double(seen) : 0.0;
  spdlog::info("albedo: the photo's edges lie up to {:.2f} px from the illumination's, on {:.2f} % of the view",
               albedo.edge_offset_px, share);
  if (albedo.edge_offset_px > kLargeEdgeOffsetPx)
    spdlog::warn(
        "{}: the photo's edges lie up to {:.1f} pixels from the geometry's: the camera is off. {} {:.1f} % of the "
        "view (unreliable.exr); `relight register` matches the camera to the photo",
        scene.path.string(), albedo.edge_offset_px,
        aligned ? "The illumination's edges were moved onto the photo's on"
                : "The albedo shows the edges as bright and dark lines (--align-edges moves them) on",
        share);
}

// A camera's own softness (its lens, anti-aliasing filter and demosaicing)
// is about a pixel at most. Sharpening a photo that is not soft costs far
// more than leaving a soft one: the public scenes' albedos as rendered lose
// 1.4-3.2 dB sharpened as if blurred by 0.5 px, 8-11 dB by 1 px, 15-18 dB by 2.
constexpr float kMaxSharpenPx = 1.0f;

// The blur to undo in the albedo (sharpen_albedo): the photo's blur measured
// again with the illumination's edges moved onto the photo's (where
// --align-edges has not moved them already). Edges a pixel or two off (a
// camera kept as given, a model a centimetre off) leave a bright and a dark
// line by each, which the measure takes for softness and the blurred
// illumination rightly softens; sharpening the albedo by it would sharpen
// the photo's own texture. Moved onto the photo's, they are not taken for
// softness, and a photo that is soft is still found so.
float blur_with_edges_met(const Image& photo, const IlluminationImages& illumination, const GBuffer& gbuffer,
                          const PhotoBlur& blur, bool edges_moved, const IlluminationAlignment& alignment) {
  if (blur.sigma_px > kMaxSharpenPx) {
    spdlog::info(
        "the albedo left as soft as the photo: a blur of {:.2f} px is more than a camera's own, and more "
        "likely the geometry's or the lights' edges off the photo's",
        blur.sigma_px);
    return 0.0f;
  }
  if (edges_moved) return blur.sigma_px;
  const PhotoBlur met =
      measure_photo_blur(photo, {alignment.align(illumination.surface).illumination, illumination.background}, gbuffer);
  if (met.sigma_px < blur.sigma_px)
    spdlog::info("with the illumination's edges moved onto the photo's, its blur is {:.2f} px", met.sigma_px);
  return std::min(met.sigma_px, blur.sigma_px);
}

// The renders an analysis by path tracing runs, in order, for the time
// left of the whole (Progress::plan_job): the direct light, then each render
// of the bounce light. Their work is counted in rays, roughly (the estimate
// goes by these only until a render of the kind has run, and by the
// render's own pace once a twentieth of it is done): a direct light sample
// is one; a path kRaysPerPath (its first ray, and the environment's shadow
// ray where it starts) and kRaysPerVertex for each surface it meets after
// (a light's shadow ray, the environment's, the ray on), as many as
// PathLengths finds; and each render's filtering, interpolation and
// division kPixelWork per pixel of the photo.
constexpr double kRaysPerPath = 2.0, kRaysPerVertex = 3.0, kPixelWork = 8.0;

// The mean surfaces a path meets after its first (mean_path_vertices): one
// that ends where it meets the photo's radiance, and one traced through
// every bounce off a mid grey (the albedo found is not known yet). In a
// closed room the second bounces on several times; under an open sky,
// hardly at all.
struct PathLengths {
  double photo = 0.0, full = 0.0;
};
constexpr int kSurveyedPaths = 4096;

PathLengths surveyed_path_lengths(const RayScene& rays, const Lighting& lighting, const GBuffer& gbuffer,
                                  const IntegratorOptions& integrator_options, const PhotoRadiance* photo_radiance,
                                  uint64_t seed) {
  const UniformAlbedo grey(AlbedoImages().mean);
  const auto survey = [&](const KnownRadiance* known) {
    return mean_path_vertices(gbuffer, Integrator(rays, lighting, &grey, integrator_options, known), kSurveyedPaths,
                              seed);
  };
  return {photo_radiance ? survey(photo_radiance) : 0.0, survey(nullptr)};
}

std::vector<JobEstimate::Stage> analysis_stages(const GBuffer& gbuffer, const AnalysisOptions& options,
                                                const IlluminationOptions& bounce_options, bool photo_radiance,
                                                int passes, const PathLengths& lengths) {
  enum Kind { direct_light, photo_paths, full_paths };
  const int w = gbuffer.width(), h = gbuffer.height(), s = indirect_stride(bounce_options, w, h);
  const double pixels = double(w) * h, traced = double((w + s - 1) / s) * double((h + s - 1) / s);
  const Kind bounce_kind = photo_radiance ? photo_paths : full_paths;
  const auto render = [&](const std::string& label, Kind kind, int paths) {
    const double rays = kRaysPerPath + kRaysPerVertex * (kind == photo_paths ? lengths.photo : lengths.full);
    return JobEstimate::Stage{label, kind, rays * traced * paths + kPixelWork * pixels};
  };
  std::vector<JobEstimate::Stage> stages = {
      {"direct light", direct_light,
       pixels * (direct_samples_per_pixel(options.paths_per_pixel, gbuffer) + kPixelWork)},
      render(photo_radiance ? "illumination" : "initial illumination", bounce_kind, bounce_options.paths_per_pixel)};
  for (int it = 0; options.interreflection && it < passes; ++it)
    stages.push_back(render("interreflection " + std::to_string(it + 1), bounce_kind, bounce_options.paths_per_pixel));
  if (photo_radiance)
    stages.push_back(render("rendered back", full_paths, options.paths_per_pixel));
  else
    stages.push_back(render("residual", full_paths, std::max(1, options.paths_per_pixel / kResidualPathsDivisor)));
  return stages;
}

// Plans the analysis's stages on `progress` for as long as it lives.
class PlannedJob {
 public:
  PlannedJob(Progress& progress, std::vector<JobEstimate::Stage> stages) : progress_(progress) {
    progress_.plan_job(std::move(stages));
  }
  ~PlannedJob() { progress_.end_job(); }
  PlannedJob(const PlannedJob&) = delete;
  PlannedJob& operator=(const PlannedJob&) = delete;

 private:
  Progress& progress_;
};

IntegratorOptions glossy_integrator_options(const SurfaceGloss& gloss, const AnalysisOptions& options) {
  IntegratorOptions o;
  o.max_bounces = options.max_bounces;
  o.gloss = &gloss;
  return o;
}

}  // namespace

PhotoSpecular::PhotoSpecular(const RayScene& rays, const Lighting& lighting, const SurfaceGloss& gloss,
                             const PhotoRadiance* photo_radiance, const AnalysisOptions& options)
    : unseen_(AlbedoImages().mean),
      integrator_(rays, lighting, &unseen_, glossy_integrator_options(gloss, options), photo_radiance),
      photo_radiance_(photo_radiance),
      surfaces_([this](const SurfacePoint& hit, Rng& rng) -> Vec3 {
        if (photo_radiance_)
          if (const std::optional<Vec3> shown = photo_radiance_->at(hit)) return *shown;
        return unseen_.at(hit).cwiseProduct(integrator_.illumination(hit, rng));
      }),
      specular_(integrator_, gloss, surfaces_) {}

void bring_to_analysis_units(Image& photo, const Analysis& analysis) {
  if (analysis.photo_vignetting) remove_vignetting(photo, *analysis.photo_vignetting);
  if (analysis.photo_exposure != Vec3::Ones()) apply_exposure(photo, analysis.photo_exposure.cwiseInverse());
}

Image photo_highlights(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const Lighting& lighting,
                       const SurfaceGloss& gloss, const PhotoRadiance* photo_radiance, const AnalysisOptions& options,
                       Progress& progress, const std::string& label) {
  const PhotoSpecular specular(rays, lighting, gloss, photo_radiance, options);
  return render_specular(gbuffer, scene.camera, specular.reflection(), options.paths_per_pixel, options.seed, progress,
                         label);
}

namespace {

// Takes c x specular off each pixel of `photo` (c its coverage), and returns
// 1 per pixel where that was over kHighlightShare of it.
std::vector<uint8_t> take_off_highlights(Image& photo, const Image& specular, const std::vector<float>& coverage) {
  std::vector<uint8_t> highlights(photo.size(), 0);
  size_t marked = 0;
  for (size_t i = 0; i < photo.size(); ++i) {
    const Vec3 highlight = coverage[i] * specular.pixels[i];
    if (highlight.isZero()) continue;
    if (luminance(highlight) > kHighlightShare * luminance(photo.pixels[i])) highlights[i] = 1, ++marked;
    photo.pixels[i] = (photo.pixels[i] - highlight).cwiseMax(0.0f);
  }
  spdlog::info("highlights taken off the photo; {:.2f} % of the view mostly highlight, filled from its surface",
               100.0 * double(marked) / double(photo.size()));
  return highlights;
}

}  // namespace

Analysis analyze(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const AnalysisOptions& requested,
                 Progress& progress, const AlbedoObserver& on_albedo) {
  check_strategy(scene, requested.strategy);
  AnalysisOptions options = requested;
  if (options.indirect_stride <= 0) options.indirect_stride = sparse_indirect_stride(gbuffer.width(), gbuffer.height());
  Analysis result;
  result.options = options;
  // The photo's radiance serves the interreflection.
  if (!options.interreflection) result.options.bounce_source = BounceSource::albedo;
  result.coverage = gbuffer.coverage();
  const Lighting lighting = strategy_lighting(scene, rays, options.strategy);
  IntegratorOptions integrator_options;
  integrator_options.max_bounces = options.max_bounces;
  integrator_options.gloss = &scene.gloss;
  std::unique_ptr<RadiosityIllumination> radiosity;
  if (options.method == AnalysisMethod::radiosity)
    radiosity =
        std::make_unique<RadiosityIllumination>(scene, rays, gbuffer, lighting, radiosity_options(options),
                                                options.direct_per_pixel, illumination_options(options), progress);
  // The photo as it is divided: its lens's vignetting divided out, in the
  // probes' units where its exposure is not theirs (the light it bounces
  // must be in the units of the light the probes give), and less the
  // highlights of glossy surfaces (below).
  const bool glossy = sees_gloss(gbuffer, scene.gloss);
  Image photo_own;
  const PhotoUnits units = photo_units_against_the_probes(scene, rays, gbuffer, options.keep_vignetting);
  if (units.exposure)
    spdlog::warn(
        "{}: the photo shows the surfaces {:.2f} times as bright as the probe {} does: it is divided by that, "
        "so the albedo and every re-lit image are in the probe's units and the lights'. `relight fit` brings "
        "the probe and the lights to the photo's instead",
        scene.path.string(), luminance(*units.exposure), units.exposure_probe);
  result.photo_vignetting = units.vignetting;
  result.photo_exposure = units.exposure.value_or(Vec3::Ones());
  const bool own = units.vignetting || units.exposure || glossy;
  if (own) bring_to_analysis_units(photo_own = scene.photo, result);
  const Image& photo = own ? photo_own : scene.photo;
  // Light bounced off what the photo shows is the photo's radiance there;
  // `albedo` then matters only on the surfaces the camera does not see.
  std::unique_ptr<PhotoRadiance> photo_radiance;
  if (result.options.bounce_source == BounceSource::photo) {
    photo_radiance = std::make_unique<PhotoRadiance>(scene.camera, gbuffer, photo, scene.probes, rays, scene.lights);
    spdlog::info("photo radiance usable on {:.1f} % of the geometry's pixels", 100.0 * photo_radiance->usable_share());
  }
  std::vector<uint8_t> unreliable = scene.photo_clipped;
  if (glossy) {
    // The highlights are taken off the photo in place: the photo's radiance
    // reads it, and what a surface bounces on is its diffuse light.
    result.specular =
        photo_highlights(scene, rays, gbuffer, lighting, scene.gloss, photo_radiance.get(), options, progress);
    result.highlights = take_off_highlights(photo_own, result.specular, result.coverage);
    if (unreliable.empty()) unreliable.assign(result.highlights.size(), 0);
    for (size_t i = 0; i < unreliable.size(); ++i) unreliable[i] |= result.highlights[i];
  }
  // The illumination with `albedo` on the surfaces light bounces off (and
  // with the photo's radiance where `known` gives it).
  // The lights' direct light does not depend on that albedo: it is rendered
  // once, with the closing pass's paths (the render that re-lights renders
  // the same).
  std::optional<Image> direct;
  const auto render_with = [&](const SurfaceAlbedo& albedo, const KnownRadiance* known,
                               const IlluminationOptions& pixel_options, const std::string& label) {
    if (radiosity) return radiosity->render(albedo, known);
    const Integrator integrator(rays, lighting, &albedo, integrator_options, known);
    if (!direct) direct = render_direct_part(gbuffer, integrator, illumination_options(options), progress);
    return render_illumination(gbuffer, scene.camera, integrator, pixel_options, progress, label, &*direct);
  };
  // With the photo's radiance, the renders before the closing pass only
  // give the albedo the closing pass's paths bounce off, and they average
  // its noise over the hemisphere: half the paths do, but no fewer than
  // kMinBouncePaths (photo / noisy illumination is biased up where the
  // noise is large, and that bias does not average out).
  IlluminationOptions bounce_options = illumination_options(options);
  if (photo_radiance)
    bounce_options.paths_per_pixel =
        std::max(std::min(options.paths_per_pixel, kMinBouncePaths), options.paths_per_pixel / kBouncePathsDivisor);
  const auto render = [&](const SurfaceAlbedo& albedo, const std::string& label) {
    return render_with(albedo, photo_radiance.get(), bounce_options, label);
  };
  const int passes = photo_radiance ? kPhotoRadiancePasses : options.max_iterations;
  std::optional<PlannedJob> job;
  if (!radiosity)
    job.emplace(progress, analysis_stages(gbuffer, options, bounce_options, bool(photo_radiance), passes,
                                          surveyed_path_lengths(rays, lighting, gbuffer, integrator_options,
                                                                photo_radiance.get(), options.seed)));

  // photo / illumination; with align_edges, the illumination's edges moved
  // to where the photo shows them (a camera a few pixels off). Moved or not,
  // the pixels where they disagree are marked, on the illumination as
  // rendered; then the photo's softness against it, measured on the first
  // illumination (after the edges are moved: a misplaced edge is not a
  // soft one), is matched by every division (photo_blur.h).
  const IlluminationAlignment alignment(scene.photo);
  std::optional<PhotoBlur> blur;
  float sharpen_px = 0.0f;  // the blur undone in the final albedo
  const auto divide = [&](const IlluminationImages& rendered) {
    IlluminationAlignment::Mismatch mismatch;
    std::optional<IlluminationImages> moved;
    if (options.align_edges) {
      IlluminationAlignment::Aligned aligned = alignment.align(rendered.surface);
      mismatch = std::move(aligned.mismatch);
      moved = IlluminationImages{std::move(aligned.illumination), rendered.background};
    } else {
      mismatch = alignment.mismatch(rendered.surface);
    }
    const IlluminationImages& sharp = moved ? *moved : rendered;
    if (!blur) {
      blur = measure_photo_blur(photo, sharp, gbuffer);
      result.photo_blur_px = blur->sigma_px;
      if (blur->sigma_px > 0.0f) {
        spdlog::info(
            "the photo is softer than the render (a Gaussian blur of {:.2f} px): the illumination is blurred alike "
            "before the division (the albedo's roughness by its edges {:.3f} -> {:.3f}, over {} pixels)",
            blur->sigma_px, blur->roughness_sharp, blur->roughness_blurred, blur->edge_pixels);
        if (options.sharpen)
          sharpen_px = blur_with_edges_met(photo, sharp, gbuffer, *blur, moved.has_value(), alignment);
      }
    }
    AlbedoImages albedo =
        blur->sigma_px > 0.0f
            ? recover_albedo(photo, unreliable, blur_illumination(sharp, gbuffer, blur->sigma_px), gbuffer)
            : recover_albedo(photo, unreliable, sharp, gbuffer);
    albedo.edge_mismatch = std::move(mismatch.moved);
    albedo.edge_offset_px = mismatch.motion_px;
    return albedo;
  };

  // Before any albedo is known, the surfaces the photo does not show reflect
  // a neutral mid grey when the photo gives the rest (white, the thesis's
  // initial illumination, otherwise).
  result.illumination = photo_radiance ? render(UniformAlbedo(AlbedoImages().mean), "illumination")
                                       : render(WhiteAlbedo(), "initial illumination");
  if (no_light_reaches_the_view(result.illumination.surface, result.coverage))
    throw InputError(scene.path.string(), "/camera",
                     "no light reaches any surface the camera sees: is the camera inside the geometry, or every "
                     "light shut in?");
  result.albedo = divide(result.illumination);
  result.iterations = 1;
  if (on_albedo) on_albedo(result.iterations, result.albedo);

  // The recovered albedo overshoots and undershoots in turn (too little
  // bounce light makes it too bright, which makes too much bounce light), so
  // each render bounces light off the mean of the last two albedos.
  Image bounce = result.albedo.albedo;
  // The triangles the photo shows too little of take the albedo the probes
  // show them with.
  const auto unseen_triangles = [&](const SurfaceAlbedo& albedo) {
    if (!photo_radiance) return std::vector<TriangleAlbedo>();
    const std::vector<uint32_t> shown = whole_pixels_per_triangle(gbuffer, scene.mesh.triangles.size());
    std::vector<uint8_t> wanted(shown.size());
    for (size_t t = 0; t < shown.size(); ++t) wanted[t] = shown[t] < kFewPixels;
    const Integrator integrator(rays, lighting, &albedo, integrator_options, photo_radiance.get());
    return photo_radiance->probe_albedo(integrator, wanted, kProbeAlbedoPaths, options.seed);
  };
  result.albedo.unseen_triangles = unseen_triangles(PhotoAlbedo(scene.camera, gbuffer, bounce, result.albedo.mean));
  // With the photo's radiance one pass puts that albedo on what only the
  // probes show and on the pixels the photo's radiance is not read from;
  // the closing pass then divides the photo in full.
  for (int it = 0; options.interreflection && it < passes; ++it) {
    const PhotoAlbedo bounce_albedo(scene.camera, gbuffer, bounce, result.albedo.mean, result.albedo.unseen_triangles);
    // The images this pass replaces are let go before it makes their
    // successors (the light bounces off `bounce`): the analysis's memory
    // peaks in these passes.
    result.illumination = {};
    IlluminationImages illum = render(bounce_albedo, "interreflection " + std::to_string(it + 1));
    result.albedo.albedo = Image();
    result.albedo.albedo_coverage = Image();
    AlbedoImages next = divide(illum);
    next.unseen_triangles = result.albedo.unseen_triangles;
    const float change = mean_abs_change(next.albedo, bounce, result.coverage);
    for (size_t i = 0; i < bounce.size(); ++i) bounce.pixels[i] = 0.5f * (bounce.pixels[i] + next.albedo.pixels[i]);
    result.illumination = std::move(illum);
    result.albedo = std::move(next);
    ++result.iterations;
    if (on_albedo) on_albedo(result.iterations, result.albedo);
    spdlog::info("interreflection pass {}: mean albedo change {:.4f}", it + 1, change);
    if (change < options.tolerance) break;
  }

  bounce = Image();  // only the interreflection passes bounce light off it: its memory back
  // The photo rendered back from the analysis: the albedo on every surface,
  // no photo radiance (what rendering the scene's own lights gives).
  const auto render_back = [&](const IlluminationOptions& back_options, const std::string& label) {
    const PhotoAlbedo final_albedo(scene.camera, gbuffer, result.albedo.albedo, result.albedo.mean,
                                   result.albedo.unseen_triangles);
    return render_with(final_albedo, nullptr, back_options, label);
  };
  if (photo_radiance) {
    // Rendered in full, and the albedo divided by it once more: the fixed
    // point photo = albedo x L(albedo) of the renderer that re-lights, so
    // that rendering the scene's own lights with the analysis's seed gives
    // the photo back, its noise and all. The residual is taken before that
    // division, from the albedo the photo's radiance gave. The images this
    // pass replaces are let go as soon as they are not needed: the
    // analysis's memory peaks here.
    result.illumination = {};
    result.albedo.albedo_coverage = Image();  // the division below makes it again
    photo_radiance.reset();                   // the bounce renders' alone
    IlluminationImages back = render_back(illumination_options(options), "rendered back");
    direct.reset();  // the last render's
    result.residual = residual_of(photo, result.albedo.albedo, back.surface, result.coverage);
    std::vector<TriangleAlbedo> unseen = std::move(result.albedo.unseen_triangles);
    result.albedo = {};
    result.albedo = divide(back);
    result.albedo.unseen_triangles = std::move(unseen);
    result.illumination = std::move(back);
    ++result.iterations;
    if (on_albedo) on_albedo(result.iterations, result.albedo);
  } else {
    // With fewer paths: the residual compares blocks, where noise averages out.
    IlluminationOptions back_options = illumination_options(options);
    back_options.paths_per_pixel = std::max(1, options.paths_per_pixel / kResidualPathsDivisor);
    const Image back = render_back(back_options, "residual").surface;
    result.residual = residual_of(photo, result.albedo.albedo, back, result.coverage);
  }
  if (sharpen_px > 0.0f) {
    sharpen_albedo(result.albedo, gbuffer, sharpen_px);
    spdlog::info("the photo's blur of {:.2f} px undone in the albedo", sharpen_px);
  }
  report_edge_offset(scene, result.albedo, result.coverage, options.align_edges);
  if (!result.albedo.as_divided.empty())
    spdlog::info(
        "{} pixels brighter than a surface can be (albedo over {:.2f}): filled from their surface, marked "
        "in unreliable.exr",
        result.albedo.as_divided.size(), result.albedo.bright_bound);
  if (result.residual > kLargeResidual)
    spdlog::warn(
        "{}: albedo x illumination rendered back is {:.1f} % from the photo: the lights, probes or "
        "geometry do not explain it (or the analysis did not converge)",
        scene.path.string(), 100.0 * result.residual);
  return result;
}

}  // namespace relight
