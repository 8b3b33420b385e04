// relight analyze: initial illumination, albedo, mask into a folder.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <vector>

#include "analysis/albedo_atlas.h"
#include "analysis/analysed_scene.h"
#include "analysis/analysis_folder.h"
#include "analysis/view_checks.h"
#include "cli/commands.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

struct AnalyzeArgs {
  std::string scene, out, strategy, interreflection = "on", method = "path", direct_light = "pixels",
                                    bounce_source = "photo";
  bool save_renders = false, preview = false;
  AnalysisOptions options;
};

// The options of the command for a loaded scene.
AnalysisOptions options_for(const AnalyzeArgs& args, const Scene& scene) {
  AnalysisOptions options = args.preview ? preview_options(args.options) : args.options;
  options.strategy = args.strategy.empty() ? default_strategy(scene) : *parse_strategy(args.strategy);
  options.interreflection = args.interreflection == "on";
  options.method = *parse_analysis_method(args.method);
  options.bounce_source = *parse_bounce_source(args.bounce_source);
  options.direct_per_pixel = args.direct_light == "pixels";
  return options;
}

// Analyses a loaded scene (a still, or a shot's frame) into `folder`.
Analysis analyse_into(const fs::path& folder, LoadedScene& s, const AnalyzeArgs& args, Progress& progress) {
  warn_about_the_view(s.scene, *s.rays, *s.gbuffer);
  const AnalysisOptions options = options_for(args, s.scene);
  std::vector<Image> renders;  // albedo_coverage of each render, with --save-renders
  const auto keep = [&](int, const AlbedoImages& albedo) { renders.push_back(albedo.albedo_coverage); };
  Analysis analysis =
      analyze(s.scene, *s.rays, *s.gbuffer, options, progress, args.save_renders ? AlbedoObserver(keep) : nullptr);
  analysis.registered_camera = s.registered_camera;
  warn_about_albedo_above_one(s.scene.path.string(), *s.gbuffer, analysis.albedo.albedo, analysis.albedo.mean,
                              "the scene's lighting");
  OutputBatch batch;  // the renders appear with the analysis
  save_analysis(folder, analysis, s.scene);
  for (size_t i = 0; i < renders.size(); ++i)
    write_exr(folder / ("albedo_render" + std::to_string(i + 1) + ".exr"), renders[i]);
  batch.commit();
  return analysis;
}

std::string summary(const Analysis& analysis) {
  const AnalysisOptions& options = analysis.options;
  const std::string sampling = options.method == AnalysisMethod::path
                                   ? std::to_string(options.paths_per_pixel) + " spp"
                                   : "radiosity, " + std::to_string(options.node_samples) + " samples and " +
                                         std::to_string(options.gather_rays) + " rays per node";
  return fmt::format("{} ({}, {}, {} render{}, residual {:.1f} %)", options.preview ? "preview analysis" : "analysis",
                     to_string(options.strategy), sampling, analysis.iterations, analysis.iterations > 1 ? "s" : "",
                     100.0 * analysis.residual);
}

// A frame as the shot's change from frame to frame is measured: what its
// pixels see, through which camera, and its images (the photo, an albedo).
struct FrameImages {
  PixelSurfaces view;
  Camera camera;
  std::vector<Image> images;
};

// Adds to sums[i] how much image i changed from the frame before to `frame`
// where both show the same surface (change_at_shared_points); `before`
// becomes `frame`.
void add_changes(std::optional<FrameImages>& before, FrameImages frame, std::vector<double>& sums) {
  if (before) {
    const auto pairs = shared_points(before->view, before->camera, frame.view);
    for (size_t i = 0; i < sums.size(); ++i)
      sums[i] += change_at_shared_points(before->images[i], frame.images[i], pairs);
  }
  before = std::move(frame);
}

// A tracked shot: each frame analysed into its folder (shot_frame_folder),
// then the albedo fused over the frames (AlbedoAtlas) and each frame's
// albedo replaced by its view of the fused one. Says how much the photos,
// the frames' own albedos and the fused albedo change from frame to frame
// where they show the same surface (the fused one's change is its flicker).
void analyse_shot(const AnalyzeArgs& args, const Scene& scene, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<ShotFrame>& frames = scene.shot.frames;
  create_output_folder(args.out);
  AlbedoAtlas atlas(scene.mesh);
  {
    // The texels are sized for the frames' pixels: the first frame's photo
    // gives their size (the scene's still may be of another).
    const Scene first = load_shot_frame(scene, 0);
    const RayScene rays(scene.mesh);
    for (const ShotFrame& frame : frames) {
      const Camera camera(frame.camera, first.camera.width(), first.camera.height());
      atlas.size_for(PixelSurfaces::central_samples(GBuffer(camera, rays, 1, 1, scene.path.string())), camera);
    }
  }
  std::vector<double> change(2, 0.0), fused_change(1, 0.0);  // the photos', the own albedos'; the fused
  std::optional<FrameImages> before;
  for (size_t k = 0; k < frames.size(); ++k) {
    const auto frame_start = std::chrono::steady_clock::now();
    LoadedScene s =
        prepare_for_analysis(load_shot_frame(scene, k), options_for(args, scene), progress, CameraUse::for_analysis);
    const fs::path folder = shot_frame_folder(args.out, frames[k].number);
    const Analysis analysis = analyse_into(folder, s, args, progress);
    const PixelSurfaces view = PixelSurfaces::central_samples(*s.gbuffer);
    atlas.add(view, analysis.albedo.albedo, albedo_weights(analysis));
    add_changes(before, {view, s.scene.camera, {s.scene.photo, analysis.albedo.albedo}}, change);
    std::printf("frame %d (%zu of %zu): %s written to %s in %.1f s\n", frames[k].number, k + 1, frames.size(),
                summary(analysis).c_str(), folder.c_str(), seconds_since(frame_start));
    std::fflush(stdout);
  }
  before.reset();
  for (size_t k = 0; k < frames.size(); ++k) {
    const fs::path folder = shot_frame_folder(args.out, frames[k].number);
    const std::unique_ptr<AnalysedScene> analysed = AnalysedScene::from_folder(load_shot_frame(scene, k), folder);
    const PixelSurfaces view = PixelSurfaces::central_samples(analysed->gbuffer());
    Image fused = atlas.albedo_for(view, analysed->analysis().albedo.albedo);
    replace_albedo(folder, analysed->analysis(), fused);
    add_changes(before, {view, analysed->scene().camera, {std::move(fused)}}, fused_change);
  }
  std::printf("shot of %zu frames analysed into %s in %.1f s; the albedo fused over the frames (%zu texels)\n",
              frames.size(), args.out.c_str(), seconds_since(start), atlas.texels());
  if (frames.size() > 1) {
    const double n = double(frames.size() - 1);
    std::printf(
        "change from frame to frame where they show the same surface: photos %.1f %%, each frame's own "
        "albedo %.1f %%, the fused albedo %.1f %%\n",
        100.0 * change[0] / n, 100.0 * change[1] / n, 100.0 * fused_change[0] / n);
  }
}

void run_analyze(const AnalyzeArgs& args, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  Scene scene = load_scene(args.scene, progress);
  log_scene(scene, args.scene);
  if (!scene.shot.frames.empty()) {
    if (args.preview) throw InputError("--preview", "", "a preview analysis is of a still; the scene is a shot");
    return analyse_shot(args, scene, progress);
  }
  const AnalysisOptions requested = args.preview ? preview_options(args.options) : args.options;
  LoadedScene s = prepare_for_analysis(std::move(scene), requested, progress, CameraUse::for_analysis);
  const Analysis analysis = analyse_into(args.out, s, args, progress);
  std::printf("%s written to %s in %.1f s\n", summary(analysis).c_str(), args.out.c_str(), seconds_since(start));
}

}  // namespace

void add_analyze_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<AnalyzeArgs>();
  CLI::App* cmd = app.add_subcommand("analyze", "recover the albedo: divide the photo by the simulated illumination");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("-o,--out", args->out, "output folder (created)")->required();
  cmd->add_option("--strategy", args->strategy,
                  "initial illumination: lights (+ constant background), probe, or combined (lights + probes with "
                  "the lights removed); default: combined where the scene has both")
      ->check(CLI::IsMember({"lights", "probe", "combined"}));
  cmd->add_option("--method", args->method,
                  "how the initial illumination is simulated: path (path tracing, --spp paths per pixel) or "
                  "radiosity (gathering radiosity on the mesh refined along the photo's shadow edges, "
                  "--node-samples and --gather-rays per mesh vertex)")
      ->check(CLI::IsMember({"path", "radiosity"}))
      ->capture_default_str();
  cmd->add_option("--node-samples", args->options.node_samples,
                  "radiosity: samples of the lights and the environment per node")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  cmd->add_option("--gather-rays", args->options.gather_rays,
                  "radiosity: rays per node gathering the light from other surfaces")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  cmd->add_option("--direct-light", args->direct_light,
                  "radiosity: the lights' direct light traced per pixel (pixels, --spp samples: sharp shadows) "
                  "or interpolated from the mesh's vertices like the rest (nodes: the thesis's Gouraud shading)")
      ->check(CLI::IsMember({"pixels", "nodes"}))
      ->capture_default_str();
  cmd->add_option("--interreflection", args->interreflection,
                  "on: iterate the albedo with coloured interreflection; off: white diffuse surfaces (the thesis)")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--bounce-source", args->bounce_source,
                  "with interreflection: light bounced off a surface the photo or a probe shows is the "
                  "radiance shown there (photo), or the albedo times its rendered light, iterated (albedo)")
      ->check(CLI::IsMember({"photo", "albedo"}))
      ->capture_default_str();
  cmd->add_flag("--align-edges", args->options.align_edges,
                "divide the photo by an illumination whose edges (shadows, silhouettes) are moved onto the photo's "
                "where the camera is a few pixels off: no edge lines under a rig that replaces the lights, but a "
                "rig that keeps them shows theirs; `relight register` is the remedy for both");
  cmd->add_flag("--keep-camera", args->options.keep_camera,
                "analyse through the scene's camera as given; by default a camera whose view of the geometry is "
                "visibly off the photo's edges (by over 1.5 px) is registered to them first, as `relight register` does, "
                "and analysis.json keeps it for every render");
  add_keep_vignetting_flag(*cmd, args->options);
  cmd->add_flag("--sharpen", args->options.sharpen,
                "undo in the albedo a blur of the photo against the render (a lens, a sensor: found where it makes "
                "the albedo smoother by its edges) of up to a pixel, regularised so as not to raise the noise, unless "
                "the model's edges moved onto the photo's account for it; for a photo known to be soft (a model "
                "whose shadows or edges differ from the photo's can pass for a soft photo)");
  cmd->add_option("--indirect-stride", args->options.indirect_stride,
                  "the environment and bounce light (smooth) traced at every N-th pixel each way and interpolated "
                  "along the surfaces between; the lights' direct light is traced at every pixel. 1: every pixel; "
                  "0: about 524 000 pixels traced (1 at 640x480, 2 at 1280x960, 7 at 24 Mpixel)")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
  cmd->add_flag(
      "--preview", args->preview,
      "a quick analysis to look at before the full one: of the photo reduced to at most 0.5 Mpixel, an eighth "
      "of the paths (--spp / 8, at least 4), one sample per pixel; analysis.json marks it a preview, and "
      "renders of it are of the reduced size");
  cmd->add_flag("--save-renders", args->save_renders,
                "also write the albedo each render recovered, albedo_render1.exr (white surfaces), "
                "albedo_render2.exr, ... (to follow the interreflection iteration)");
  add_sampling_options(*cmd, args->options);
  cmd->footer(
      help_footer("Simulates the light the photo was taken under (from the scene's lights, probes and background) and\n"
                  "  divides the photo by it, leaving the albedo. The folder is reused by 'relight render --analysis'.",
                  {{"relight analyze examples/room/scene.json -o out/room",
                    "writes out/room/{illumination.exr, albedo.exr, albedo.png, mask.exr, analysis.json}"},
                   {"relight analyze scene.json -o analysis --strategy probe --spp 256",
                    "simulate the light from the probes only, with less noise"},
                   {"relight analyze scene.json -o analysis --method radiosity",
                    "simulate it by radiosity on a mesh refined along the photo's shadows (the thesis's method)"}}));
  run_when_parsed(*cmd, action, args, run_analyze);
}

}  // namespace relight::cli
