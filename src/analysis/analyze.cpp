#include "analysis/analyze.h"

#include <spdlog/spdlog.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "analysis/radiosity_illumination.h"
#include "analysis/surface_albedo.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/content_hash.h"
#include "io/image_io.h"
#include "io/input_file.h"
#include "io/response_curve.h"

namespace relight {

namespace fs = std::filesystem;

GBuffer scene_gbuffer(const Scene& scene, const RayScene& rays, const AnalysisOptions& options) {
  return GBuffer(scene.camera, rays, options.gbuffer_samples, options.seed, scene.path.string());
}

const char* to_string(AnalysisMethod m) { return m == AnalysisMethod::radiosity ? "radiosity" : "path"; }

std::optional<AnalysisMethod> parse_analysis_method(const std::string& s) {
  if (s == "path") return AnalysisMethod::path;
  if (s == "radiosity") return AnalysisMethod::radiosity;
  return std::nullopt;
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

// The images of the analysis folder that later renders read. analysis.json is
// written after them and records their hash, so a folder whose images are not
// the ones it describes (an analyze killed while rewriting the folder, or a
// file copied in from another analysis) is refused rather than mixed.
constexpr const char* kAnalysisImages[] = {"albedo_surface.exr", "albedo.exr", "background.exr", "mask.exr"};

// `file` names where each image is read from: the folder, or the writer's
// own temporaries before they are renamed into it (the writer hashes its own
// files, never what another writer may have put in the folder meanwhile).
std::string analysis_images_hash(const std::function<fs::path(const char* name)>& file) {
  ContentHash hash;
  for (const char* name : kAnalysisImages) hash.add_file(file(name));
  return hash.hex();
}

// An analysis replaces an analysis: a folder holding files of its names but
// no analysis.json (a scene's own folder with its mask.exr, say) is refused
// unless forced, so that nothing of someone else's is overwritten.
void expect_analysis_folder(const fs::path& folder) {
  if (force_outputs() || fs::exists(folder / "analysis.json")) return;
  for (const char* name :
       {"illumination.exr", "background.exr", "albedo.exr", "albedo_surface.exr", "albedo.png", "mask.exr"})
    if (fs::exists(fs::symlink_status(folder / name)))
      throw InputError(folder.string(), "",
                       std::string("is not an analysis folder (no analysis.json) but holds ") + name +
                           ", which an analysis would replace; name another folder, or --force to replace it");
}

}  // namespace

Analysis analyze(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const AnalysisOptions& options,
                 Progress& progress, const AlbedoObserver& on_albedo) {
  check_strategy(scene, options.strategy);
  Analysis result;
  result.options = options;
  result.coverage = gbuffer.coverage();
  const Lighting lighting = strategy_lighting(scene, rays, options.strategy);
  IntegratorOptions integrator_options;
  integrator_options.max_bounces = options.max_bounces;
  std::unique_ptr<RadiosityIllumination> radiosity;
  if (options.method == AnalysisMethod::radiosity)
    radiosity = std::make_unique<RadiosityIllumination>(scene, rays, gbuffer, lighting, radiosity_options(options),
                                                        options.direct_per_pixel, illumination_options(options),
                                                        progress);
  // The illumination with `albedo` on the surfaces light bounces off.
  const auto render = [&](const SurfaceAlbedo& albedo, const std::string& label) {
    if (radiosity) return radiosity->render(albedo);
    const Integrator integrator(rays, lighting, &albedo, integrator_options);
    return render_illumination(gbuffer, scene.camera, integrator, illumination_options(options), progress, label);
  };

  result.illumination = render(WhiteAlbedo(), "initial illumination");
  if (no_light_reaches_the_view(result.illumination.surface, result.coverage))
    throw InputError(scene.path.string(), "/camera",
                     "no light reaches any surface the camera sees: is the camera inside the geometry, or every "
                     "light shut in?");
  result.albedo = recover_albedo(scene.photo, scene.photo_clipped, result.illumination, gbuffer);
  result.iterations = 1;
  if (on_albedo) on_albedo(result.iterations, result.albedo);

  // The recovered albedo overshoots and undershoots in turn (too little
  // bounce light makes it too bright, which makes too much bounce light), so
  // each render bounces light off the mean of the last two albedos.
  Image bounce = result.albedo.albedo;
  for (int it = 0; options.interreflection && it < options.max_iterations; ++it) {
    const PhotoAlbedo bounce_albedo(scene.camera, gbuffer, bounce, result.albedo.mean);
    IlluminationImages illum = render(bounce_albedo, "interreflection " + std::to_string(it + 1));
    AlbedoImages next = recover_albedo(scene.photo, scene.photo_clipped, illum, gbuffer);
    const float change = mean_abs_change(next.albedo, bounce, result.coverage);
    for (size_t i = 0; i < bounce.size(); ++i) bounce.pixels[i] = 0.5f * (bounce.pixels[i] + next.albedo.pixels[i]);
    result.illumination = std::move(illum);
    result.albedo = std::move(next);
    ++result.iterations;
    if (on_albedo) on_albedo(result.iterations, result.albedo);
    spdlog::info("interreflection pass {}: mean albedo change {:.4f}", it + 1, change);
    if (change < options.tolerance) break;
  }
  return result;
}

std::string analysis_input_hash(const Scene& scene, const AnalysisOptions& options) {
  ContentHash hash;
  hash.add_file(scene.path);
  hash.add_file(scene.photo_path);
  hash.add_file(scene.geometry_path);
  for (const Probe& probe : scene.probes) hash.add_file(probe.path);
  if (const ResponseCurve* response = ldr_response()) hash.add_file(response->path());  // how an LDR photo was read
  hash.add_text(fmt::format("{} {} {} {} {} {} {}", to_string(options.strategy), options.paths_per_pixel,
                            options.gbuffer_samples, options.seed, options.max_bounces, options.interreflection,
                            options.denoise));
  // Added only for radiosity, so that path analyses made before the method
  // existed stay valid.
  if (options.method == AnalysisMethod::radiosity)
    hash.add_text(fmt::format(" radiosity {} {} {}", options.node_samples, options.gather_rays,
                              options.direct_per_pixel));
  return hash.hex();
}

void save_analysis(const fs::path& folder, const Analysis& a, const Scene& scene) {
  std::error_code ec;
  fs::create_directories(folder, ec);
  if (!fs::is_directory(folder)) throw InputError(folder.string(), "", "cannot create the output folder");
  expect_analysis_folder(folder);
  OutputBatch batch;  // the files appear together, analysis.json with them; the folder is locked meanwhile
  const int w = a.albedo.albedo.width, h = a.albedo.albedo.height;
  // The illumination as a user would look at it: the white-diffuse render,
  // with the environment where the pixel sees no geometry.
  Image illumination = a.illumination.surface;
  for (size_t i = 0; i < illumination.size(); ++i)
    if (a.coverage[i] == 0.0f) illumination.pixels[i] = a.illumination.background.pixels[i];
  write_exr(folder / "illumination.exr", illumination);
  write_exr(folder / "background.exr", a.illumination.background);
  write_exr(folder / "albedo.exr", a.albedo.albedo_coverage);
  write_exr(folder / "albedo_surface.exr", a.albedo.albedo);
  write_png(folder / "albedo.png", a.albedo.albedo_coverage);
  write_exr_scalar(folder / "mask.exr", a.coverage, w, h);

  nlohmann::json j;
  j["format"] = "relight-analysis/1";
  j["input_hash"] = analysis_input_hash(scene, a.options);
  j["images_hash"] = analysis_images_hash([&](const char* name) { return batch.staged(folder / name); });
  j["method"] = to_string(a.options.method);
  j["strategy"] = to_string(a.options.strategy);
  j["paths_per_pixel"] = a.options.paths_per_pixel;
  j["gbuffer_samples"] = a.options.gbuffer_samples;
  j["seed"] = a.options.seed;
  j["max_bounces"] = a.options.max_bounces;
  j["interreflection"] = a.options.interreflection;
  j["denoise"] = a.options.denoise;
  if (a.options.method == AnalysisMethod::radiosity) {
    j["node_samples"] = a.options.node_samples;
    j["gather_rays"] = a.options.gather_rays;
    j["direct_light"] = a.options.direct_per_pixel ? "pixels" : "nodes";
  }
  j["iterations"] = a.iterations;
  j["width"] = w;
  j["height"] = h;
  j["unseen_albedo"] = {a.albedo.mean.x(), a.albedo.mean.y(), a.albedo.mean.z()};
  j["filled_pixels"] = a.albedo.filled;
  write_text_atomically(folder / "analysis.json", j.dump(2) + "\n");
  batch.commit();
}

Analysis load_analysis(const fs::path& folder, const Scene& scene) {
  const fs::path meta = folder / "analysis.json";
  if (!fs::exists(meta)) throw InputError(meta.string(), "", "not found: run 'relight analyze' into this folder first");
  const FolderLock no_writer_meanwhile(folder, FolderLock::Mode::shared);  // see OutputBatch
  expect_input_file(meta, "an analysis file (analysis.json)");
  nlohmann::json j;
  try {
    std::ifstream in(meta);
    j = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw InputError(meta.string(), "", std::string("malformed analysis file (") + e.what() + ")");
  }
  Analysis a;
  try {
    a.options.method = parse_analysis_method(j.value("method", std::string("path"))).value();
    a.options.strategy = parse_strategy(j.at("strategy").get<std::string>()).value();
    a.options.paths_per_pixel = j.at("paths_per_pixel").get<int>();
    a.options.gbuffer_samples = j.at("gbuffer_samples").get<int>();
    a.options.seed = j.at("seed").get<uint64_t>();
    a.options.max_bounces = j.at("max_bounces").get<int>();
    a.options.interreflection = j.at("interreflection").get<bool>();
    a.options.denoise = j.at("denoise").get<bool>();
    if (a.options.method == AnalysisMethod::radiosity) {
      a.options.node_samples = j.at("node_samples").get<int>();
      a.options.gather_rays = j.at("gather_rays").get<int>();
      a.options.direct_per_pixel = j.at("direct_light").get<std::string>() == "pixels";
    }
    a.iterations = j.at("iterations").get<int>();
    const auto& u = j.at("unseen_albedo");
    a.albedo.mean = Vec3(u.at(0).get<float>(), u.at(1).get<float>(), u.at(2).get<float>());
    if (j.at("width").get<int>() != scene.photo.width || j.at("height").get<int>() != scene.photo.height)
      throw InputError(meta.string(), "/width", "the analysis was made for a photo of another size");
    if (j.value("input_hash", std::string()) != analysis_input_hash(scene, a.options))
      throw InputError(meta.string(), "/input_hash",
                       "the analysis is stale: " + scene.path.string() +
                           ", its photo, geometry or probes changed since it was made; re-run 'relight analyze'");
    const auto in_folder = [&](const char* name) { return folder / name; };
    if (j.value("images_hash", std::string()) != analysis_images_hash(in_folder))
      throw InputError(meta.string(), "/images_hash",
                       "the images of the analysis are not the ones it describes (an interrupted or mixed "
                       "analysis); re-run 'relight analyze'");
  } catch (const InputError&) {
    throw;
  } catch (const std::exception& e) {
    throw InputError(meta.string(), "", std::string("incomplete analysis file (") + e.what() + ")");
  }
  a.albedo.albedo = read_image(folder / "albedo_surface.exr");
  a.albedo.albedo_coverage = read_image(folder / "albedo.exr");
  a.illumination.background = read_image(folder / "background.exr");
  int w, h;
  a.coverage = read_scalar_image(folder / "mask.exr", w, h);
  for (const Image* img : {&a.albedo.albedo, &a.albedo.albedo_coverage, &a.illumination.background})
    if (img->width != scene.photo.width || img->height != scene.photo.height)
      throw InputError(folder.string(), "", "an image of the analysis differs in size from the photo");
  if (w != scene.photo.width || h != scene.photo.height)
    throw InputError((folder / "mask.exr").string(), "", "differs in size from the photo");
  return a;
}

}  // namespace relight
