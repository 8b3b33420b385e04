#include "analysis/analysis_folder.h"

#include <fmt/format.h>

#include <nlohmann/json.hpp>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/content_hash.h"
#include "io/frame_files.h"
#include "io/image_io.h"
#include "io/input_file.h"
#include "io/json_reader.h"
#include "io/json_text.h"
#include "io/output_guard.h"
#include "io/response_curve.h"
#include "io/scene_io.h"

namespace relight {

namespace fs = std::filesystem;

namespace {

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
  for (const char* name : {"illumination.exr", "background.exr", "albedo.exr", "albedo_surface.exr", "albedo.png",
                           "mask.exr", "unreliable.exr", "specular.exr"})
    if (fs::exists(fs::symlink_status(folder / name)))
      throw InputError(folder.string(), "",
                       std::string("is not an analysis folder (no analysis.json) but holds ") + name +
                           ", which an analysis would replace; name another folder, or --force to replace it");
}

// The options analysis.json records: written and read here only.
void write_options(nlohmann::json& j, const AnalysisOptions& o) {
  j["method"] = to_string(o.method);
  j["strategy"] = to_string(o.strategy);
  j["paths_per_pixel"] = o.paths_per_pixel;
  j["gbuffer_samples"] = o.gbuffer_samples;
  j["seed"] = o.seed;
  j["max_bounces"] = o.max_bounces;
  j["interreflection"] = o.interreflection;
  j["bounce_source"] = to_string(o.bounce_source);
  j["denoise"] = o.denoise;
  j["indirect_stride"] = o.indirect_stride;
  if (o.align_edges) j["align_edges"] = true;
  if (o.keep_camera) j["keep_camera"] = true;
  if (o.keep_vignetting) j["keep_vignetting"] = true;
  if (o.sharpen) j["sharpen"] = true;
  if (o.preview) j["preview"] = true;
  if (o.method == AnalysisMethod::radiosity) {
    j["node_samples"] = o.node_samples;
    j["gather_rays"] = o.gather_rays;
    j["direct_light"] = o.direct_per_pixel ? "pixels" : "nodes";
  }
}

// A folder made before a key existed reads as what it was made with then:
// method path, bounce source albedo.
AnalysisOptions read_options(const JsonReader& r, const nlohmann::json& j) {
  const auto count = [&](const char* key) {
    return int(r.unsigned_integer(r.required(j, "", key), json_child("", key), INT32_MAX));
  };
  const auto named = [&](const char* key, const char* absent, auto parse) {
    const nlohmann::json* v = r.optional(j, key);
    const std::string name = v ? r.string(*v, json_child("", key)) : absent;
    const auto parsed = parse(name);
    if (!parsed) r.fail(json_child("", key), "unknown value '" + name + "'");
    return *parsed;
  };
  AnalysisOptions o;
  o.method = named("method", "path", parse_analysis_method);
  o.strategy = named("strategy", "", parse_strategy);
  o.paths_per_pixel = count("paths_per_pixel");
  o.gbuffer_samples = count("gbuffer_samples");
  o.seed = r.unsigned_integer(r.required(j, "", "seed"), "/seed");
  o.max_bounces = count("max_bounces");
  o.interreflection = r.boolean(r.required(j, "", "interreflection"), "/interreflection");
  o.bounce_source = named("bounce_source", "albedo", parse_bounce_source);
  o.denoise = r.boolean(r.required(j, "", "denoise"), "/denoise");
  // Before the key existed, every pixel was traced.
  o.indirect_stride = r.optional(j, "indirect_stride") ? count("indirect_stride") : 1;
  if (o.indirect_stride < 1) r.fail("/indirect_stride", "must be at least 1");
  if (const nlohmann::json* v = r.optional(j, "align_edges")) o.align_edges = r.boolean(*v, "/align_edges");
  if (const nlohmann::json* v = r.optional(j, "keep_camera")) o.keep_camera = r.boolean(*v, "/keep_camera");
  if (const nlohmann::json* v = r.optional(j, "keep_vignetting")) o.keep_vignetting = r.boolean(*v, "/keep_vignetting");
  if (const nlohmann::json* v = r.optional(j, "sharpen")) o.sharpen = r.boolean(*v, "/sharpen");
  if (const nlohmann::json* v = r.optional(j, "preview")) o.preview = r.boolean(*v, "/preview");
  if (o.method == AnalysisMethod::radiosity) {
    o.node_samples = count("node_samples");
    o.gather_rays = count("gather_rays");
    o.direct_per_pixel = r.string(r.required(j, "", "direct_light"), "/direct_light") == "pixels";
  }
  return o;
}

// 1 where the division was not trusted for its edges, for a highlight or for
// an albedo brighter than a surface can be, 0 elsewhere.
std::vector<float> unreliable_marks(const Analysis& a) {
  std::vector<float> marks(a.albedo.albedo.size(), 0.0f);
  for (size_t i = 0; i < a.albedo.edge_mismatch.size() && i < marks.size(); ++i) marks[i] = a.albedo.edge_mismatch[i];
  for (size_t i = 0; i < a.highlights.size() && i < marks.size(); ++i)
    marks[i] = std::max<float>(marks[i], a.highlights[i]);
  for (const auto& [i, albedo] : a.albedo.as_divided)
    if (i < marks.size()) marks[i] = 1.0f;
  return marks;
}

}  // namespace

fs::path shot_frame_folder(const fs::path& analysis, int frame) { return frame_file(analysis / "frame.####", frame); }

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
  // Added only for the photo's radiance, so that analyses made before it
  // existed stay valid.
  if (options.bounce_source == BounceSource::photo) hash.add_text(" bounce-source photo");
  if (options.align_edges) hash.add_text(" align-edges");  // likewise
  if (options.keep_camera) hash.add_text(" keep-camera");  // likewise
  if (options.keep_vignetting) hash.add_text(" keep-vignetting");  // likewise
  if (options.sharpen) hash.add_text(" sharpen");                  // likewise
  if (options.indirect_stride != 1) hash.add_text(fmt::format(" indirect-stride {}", options.indirect_stride));
  // Added only for radiosity, so that path analyses made before the method
  // existed stay valid.
  if (options.method == AnalysisMethod::radiosity)
    hash.add_text(
        fmt::format(" radiosity {} {} {}", options.node_samples, options.gather_rays, options.direct_per_pixel));
  return hash.hex();
}

void save_analysis(const fs::path& folder, const Analysis& a, const Scene& scene) {
  create_output_folder(folder);
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
  write_exr_scalar(folder / "unreliable.exr", unreliable_marks(a), w, h);
  if (!a.specular.pixels.empty()) write_exr(folder / "specular.exr", a.specular);

  nlohmann::json j;
  j["format"] = "relight-analysis/1";
  j["input_hash"] = analysis_input_hash(scene, a.options);
  j["images_hash"] = analysis_images_hash([&](const char* name) { return batch.staged(folder / name); });
  write_options(j, a.options);
  j["iterations"] = a.iterations;
  j["residual"] = a.residual;
  j["width"] = w;
  j["height"] = h;
  j["unseen_albedo"] = {a.albedo.mean.x(), a.albedo.mean.y(), a.albedo.mean.z()};
  if (a.photo_exposure != Vec3::Ones())
    j["photo_exposure"] = {a.photo_exposure.x(), a.photo_exposure.y(), a.photo_exposure.z()};
  if (a.photo_vignetting) j["photo_vignetting"] = {{"r2", a.photo_vignetting->r2}, {"r4", a.photo_vignetting->r4}};
  if (a.photo_blur_px > 0.0f) j["photo_blur_px"] = a.photo_blur_px;
  if (a.registered_camera) j["camera"] = camera_to_json(*a.registered_camera);
  j["filled_pixels"] = a.albedo.filled;
  nlohmann::json triangles = nlohmann::json::array();
  for (const TriangleAlbedo& t : a.albedo.unseen_triangles)
    triangles.push_back({t.triangle, t.albedo.x(), t.albedo.y(), t.albedo.z()});
  j["unseen_triangles"] = std::move(triangles);
  nlohmann::json as_divided = nlohmann::json::array();
  for (const auto& [pixel, albedo] : a.albedo.as_divided)
    as_divided.push_back({pixel, albedo.x(), albedo.y(), albedo.z()});
  j["as_divided"] = std::move(as_divided);
  write_text_atomically(folder / "analysis.json", json_text(j));
  batch.commit();
  // An analysis of a scene that no longer shines leaves no highlights of an older one.
  std::error_code ignored;
  if (a.specular.pixels.empty()) fs::remove(folder / "specular.exr", ignored);
}

void replace_albedo(const fs::path& folder, const Analysis& analysis, const Image& albedo) {
  if (albedo.width != analysis.albedo.albedo.width || albedo.height != analysis.albedo.albedo.height)
    throw std::invalid_argument("replace_albedo: the albedo is not the analysis's size");
  Image albedo_coverage = albedo;
  for (size_t i = 0; i < albedo.size(); ++i) albedo_coverage.pixels[i] *= analysis.coverage[i];
  nlohmann::json j = JsonReader::parse_file(folder / "analysis.json");
  j.erase("as_divided");  // the new albedo is re-lit as it is everywhere
  // Read above, rewritten here: the files this function exists to replace.
  for (const char* name : {"albedo.exr", "albedo_surface.exr", "albedo.png", "analysis.json"})
    allow_replacing_input(folder / name);
  OutputBatch batch;
  write_exr(folder / "albedo.exr", albedo_coverage);
  write_exr(folder / "albedo_surface.exr", albedo);
  write_png(folder / "albedo.png", albedo_coverage);
  j["images_hash"] = analysis_images_hash([&](const char* name) {
    const fs::path file = folder / name;
    return std::string_view(name).starts_with("albedo") ? batch.staged(file) : file;
  });
  write_text_atomically(folder / "analysis.json", json_text(j));
  batch.commit();
}

bool is_preview_analysis(const fs::path& folder) {
  try {
    const nlohmann::json j = JsonReader::parse_file(folder / "analysis.json");
    return j.is_object() && j.value("preview", false);
  } catch (const std::exception&) {
    return false;
  }
}

Analysis load_analysis(const fs::path& folder, const Scene& scene) {
  const fs::path meta = folder / "analysis.json";
  if (!fs::exists(meta)) throw InputError(meta.string(), "", "not found: run 'relight analyze' into this folder first");
  const FolderLock no_writer_meanwhile(folder, FolderLock::Mode::shared);  // see OutputBatch
  expect_input_file(meta, "an analysis file (analysis.json)");
  const nlohmann::json j = JsonReader::parse_file(meta);
  const JsonReader r(meta.string());
  r.expect_object(j, "");
  Analysis a;
  a.options = read_options(r, j);
  a.iterations = int(r.unsigned_integer(r.required(j, "", "iterations"), "/iterations", INT32_MAX));
  if (const nlohmann::json* residual = r.optional(j, "residual")) a.residual = r.number(*residual, "/residual", 0.0f);
  a.albedo.mean = r.vec3(r.required(j, "", "unseen_albedo"), "/unseen_albedo");
  if (const nlohmann::json* e = r.optional(j, "photo_exposure")) {
    a.photo_exposure = r.vec3(*e, "/photo_exposure");
    if (!(a.photo_exposure.minCoeff() > 0.0f) || !a.photo_exposure.allFinite())
      r.fail("/photo_exposure", "expected three positive numbers");
  }
  if (const nlohmann::json* v = r.optional(j, "photo_vignetting")) {
    r.expect_object(*v, "/photo_vignetting");
    a.photo_vignetting = Vignetting{r.number(r.required(*v, "/photo_vignetting", "r2"), "/photo_vignetting/r2"),
                                    r.number(r.required(*v, "/photo_vignetting", "r4"), "/photo_vignetting/r4")};
  }
  if (const nlohmann::json* blur = r.optional(j, "photo_blur_px"))
    a.photo_blur_px = r.number(*blur, "/photo_blur_px", 0.0f);
  if (const nlohmann::json* camera = r.optional(j, "camera"))
    a.registered_camera = camera_from_json(r, *camera, "/camera");
  const uint64_t width = r.unsigned_integer(r.required(j, "", "width"), "/width");
  const uint64_t height = r.unsigned_integer(r.required(j, "", "height"), "/height");
  if (width != uint64_t(scene.photo.width) || height != uint64_t(scene.photo.height))
    r.fail("/width", "the analysis was made for a photo of another size");
  // [index, r, g, b] entries: an index below `count`, and an albedo.
  const auto indexed_albedos = [&](const char* key, uint64_t count, const char* index_name, const char* out_of_range,
                                   const auto& add) {
    const nlohmann::json* list = r.optional(j, key);
    if (!list) return;
    const std::string where = json_child("", key);
    if (!list->is_array()) r.fail(where, "expected an array");
    for (size_t k = 0; k < list->size(); ++k) {
      const nlohmann::json& t = (*list)[k];
      const std::string at = json_child(where, k);
      if (!t.is_array() || t.size() != 4) r.fail(at, fmt::format("expected [{}, r, g, b]", index_name));
      const uint64_t index = r.unsigned_integer(t[0], json_child(at, size_t(0)));
      if (index >= count) r.fail(at, out_of_range);
      add(uint32_t(index), Vec3(r.number(t[1], json_child(at, size_t(1))), r.number(t[2], json_child(at, size_t(2))),
                                r.number(t[3], json_child(at, size_t(3)))));
    }
  };
  indexed_albedos("unseen_triangles", scene.mesh.triangles.size(), "triangle",
                  "names a triangle the geometry does not have", [&](uint32_t t, const Vec3& albedo) {
                    a.albedo.unseen_triangles.push_back({t, albedo});
                  });
  indexed_albedos("as_divided", width * height, "pixel", "names a pixel past the photo's",
                  [&](uint32_t i, const Vec3& albedo) { a.albedo.as_divided.emplace_back(i, albedo); });
  const auto text = [&](const char* key) {
    const nlohmann::json* v = r.optional(j, key);
    return v ? r.string(*v, json_child("", key)) : std::string();
  };
  if (text("input_hash") != analysis_input_hash(scene, a.options))
    r.fail("/input_hash", "the analysis is stale: " + scene.path.string() +
                              ", its photo, geometry or probes changed since it was made; re-run 'relight analyze'");
  const auto in_folder = [&](const char* name) { return folder / name; };
  if (text("images_hash") != analysis_images_hash(in_folder))
    r.fail("/images_hash",
           "the images of the analysis are not the ones it describes (an interrupted or mixed analysis); re-run "
           "'relight analyze'");
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
