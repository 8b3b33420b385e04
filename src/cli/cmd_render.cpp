// relight render: the photo under a new rig.
#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "analysis/analysis_folder.h"
#include "cli/commands.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/frame_files.h"
#include "io/image_io.h"
#include "io/scene_io.h"
#include "relight/frame_sequence.h"
#include "relight/render_rig.h"
#include "scene/animation.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

struct RenderArgs {
  std::string scene, rig, out, analysis, frames;
  AnalysisOptions options;
  const CLI::Option* spp = nullptr;  // given or not
  float exposure = 0.0f;
};

// The EXR and the PNG beside it, appearing together; their paths.
std::pair<fs::path, fs::path> write_relit(fs::path out, const Image& image, float exposure) {
  if (out.extension() != ".exr") out += ".exr";
  fs::path png = out;
  png.replace_extension(".png");
  OutputBatch pair;
  write_exr(out, image);
  write_png(png, image, exposure);
  pair.commit();
  return {out, png};
}

// The frames asked for, checked against the output name and the rig.
std::optional<FrameRange> frames_to_render(const RenderArgs& args, const Rig& rig) {
  const std::optional<FrameRange> keyed = keyed_frames(rig);
  if (args.frames.empty()) {
    if (has_frame_digits(args.out))
      throw InputError(
          args.out, "",
          "the output names a frame sequence ('#'): give the frames with --frames" +
              (keyed ? " (the rig's keys span " + std::to_string(keyed->first) + "-" + std::to_string(keyed->last) + ")"
                     : std::string()));
    if (keyed)
      spdlog::warn(
          "{}: the rig is animated (keys on frames {}-{}); rendering its lights as they stand outside the "
          "animation: --frames renders the frames",
          args.rig, keyed->first, keyed->last);
    return std::nullopt;
  }
  const FrameRange frames = frames_option(args.frames);
  if (!has_frame_digits(args.out))
    throw InputError(args.out, "",
                     "a frame sequence needs '#' in the output's name for the frame number "
                     "(relit.####.exr)");
  if (!keyed) spdlog::warn("{}: the rig has no keys: every frame is the same", args.rig);
  return frames;
}

void render_frames(const RenderArgs& args, const AnalysedScene& analysed, const Rig& rig, FrameRange frames,
                   const RenderOptions& options, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  FrameSequence sequence(analysed, rig, options);
  const int count = frames.last - frames.first + 1;
  double first_frame = 0.0;
  for (int frame = frames.first; frame <= frames.last; ++frame) {
    const auto frame_start = std::chrono::steady_clock::now();
    const FrameSequence::Stats before = sequence.stats();
    const Image image = sequence.render(frame, progress);
    const fs::path out = write_relit(frame_file(args.out, frame), image, args.exposure).first;
    const FrameSequence::Stats& after = sequence.stats();
    const int done = frame - frames.first + 1;
    // The first frame renders the still part too: the time left goes by the
    // others' (known from the second frame on).
    if (done == 1) first_frame = seconds_since(frame_start);
    const std::string left =
        done == count ? "done"
        : done == 1
            ? "the time left follows the next frame"
            : fmt::format("about {:.0f} s left", (seconds_since(start) - first_frame) / (done - 1) * (count - done));
    std::printf("frame %d (%d of %d): %s%d keyed light(s) rendered, %d reused, %.1f s; %s written; %s\n", frame, done,
                count, after.still_renders > before.still_renders ? "the still part and " : "",
                after.light_renders - before.light_renders, after.light_reuses - before.light_reuses,
                seconds_since(frame_start), out.c_str(), left.c_str());
    std::fflush(stdout);
  }
  const FrameSequence::Stats& stats = sequence.stats();
  std::printf("%d frames written to %s in %.1f s (%d renders of keyed lights, %d reused from the frame before)\n",
              count, args.out.c_str(), seconds_since(start), stats.light_renders, stats.light_reuses);
}

// A tracked shot: each frame re-lit from its analysis (relight analyze's
// frame folders, whose albedo is fused over the shot), the rig at that
// frame where it is animated.
void render_shot(const RenderArgs& args, const Scene& scene, const Rig& rig, const RenderOptions& options,
                 Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  if (args.analysis.empty())
    throw InputError(args.scene, "",
                     "is a shot: analyse it first (relight analyze, which fuses the albedo over its frames) and "
                     "give the folder with --analysis");
  if (!has_frame_digits(args.out))
    throw InputError(args.out, "", "a shot renders a frame sequence: name the output with '#'s (relit.####.exr)");
  std::optional<FrameRange> only;
  if (!args.frames.empty()) only = frames_option(args.frames);
  create_output_folder(fs::path(args.out).parent_path().empty() ? fs::path(".") : fs::path(args.out).parent_path());
  const std::vector<ShotFrame>& frames = scene.shot.frames;
  int written = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    const int number = frames[k].number;
    if (only && (number < only->first || number > only->last)) continue;
    const auto frame_start = std::chrono::steady_clock::now();
    const std::unique_ptr<AnalysedScene> analysed =
        AnalysedScene::from_folder(load_shot_frame(scene, k), shot_frame_folder(args.analysis, number));
    RenderOptions frame_options = options;
    if (!args.spp->count()) frame_options.paths_per_pixel = analysed->analysis().options.paths_per_pixel;
    const Image image = render_rig(*analysed, rig_at_frame(rig, number), frame_options, progress);
    const fs::path out = write_relit(frame_file(args.out, number), image, args.exposure).first;
    ++written;
    std::printf("frame %d (%zu of %zu): %s written in %.1f s\n", number, k + 1, frames.size(), out.c_str(),
                seconds_since(frame_start));
    std::fflush(stdout);
  }
  if (written == 0) throw InputError("--frames", "", "no frame of the shot is in " + args.frames);
  std::printf("%d frames of the shot written to %s in %.1f s\n", written, args.out.c_str(), seconds_since(start));
}

void run_render(const RenderArgs& args, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const Rig rig = load_rig(args.rig);
  Scene scene = load_scene(args.scene, progress);
  log_scene(scene, args.scene);
  RenderOptions render_options;
  render_options.paths_per_pixel = args.options.paths_per_pixel;
  render_options.max_bounces = args.options.max_bounces;
  if (!scene.shot.frames.empty()) return render_shot(args, scene, rig, render_options, progress);
  const std::optional<FrameRange> frames = frames_to_render(args, rig);
  // A sequence's folder is made, as Blender makes its; a still's must exist.
  // Either way before the long work.
  const fs::path folder = fs::path(args.out).parent_path();
  if (std::error_code error; frames && !folder.empty() && !fs::exists(folder)) {
    if (!fs::create_directories(folder, error))
      throw InputError(args.out, "", "cannot make the output folder: " + error.message());
    spdlog::info("made the folder {} for the frames", folder.string());
  }
  check_output_folder(args.out);
  const std::unique_ptr<AnalysedScene> analysed =
      analysed_scene(std::move(scene), args.analysis, args.options, progress);
  // By default the analysis's paths: with its seed, the render's noise then
  // follows the analysis's, and the scene's own lights give back the photo.
  if (!args.spp->count()) render_options.paths_per_pixel = analysed->analysis().options.paths_per_pixel;
  if (frames) return render_frames(args, *analysed, rig, *frames, render_options, progress);
  const Image image = render_rig(*analysed, rig, render_options, progress);
  const auto [out, png] = write_relit(args.out, image, args.exposure);
  std::printf("re-lit image written to %s and %s in %.1f s\n", out.c_str(), png.c_str(), seconds_since(start));
}

}  // namespace

void add_render_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "render the photo under a new lighting design (rig.json)");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("--rig", args->rig, "rig.json: the new lights")->required();
  cmd->add_option("-o,--out", args->out,
                  "output EXR; a tone-mapped PNG is written beside it. With --frames, '#'s stand for the frame "
                  "number (relit.####.exr)")
      ->required();
  cmd->add_option("--frames", args->frames,
                  "render the frames of an animated rig: a frame (12) or a range (1-120); each light is rendered "
                  "only when it moved since the frame before");
  cmd->add_option("--analysis", args->analysis,
                  "an analysis folder from 'relight analyze' to reuse (else the scene is analysed first)");
  cmd->add_option("--exposure", args->exposure, "exposure of the PNG in stops")->capture_default_str();
  add_sampling_options(*cmd, args->options);
  args->spp = cmd->get_option("--spp")->default_str("")->description(
      "light paths per pixel (more: less noise, slower); default: the analysis's, with which the scene's own "
      "lights give back the photo, its noise and all");
  cmd->footer(help_footer(
      "Renders the photo under the rig's lights: the albedo times the new illumination. Writes OUT.exr and a\n"
      "  tone-mapped PNG beside it. Without --analysis the scene is analysed first with the defaults.",
      {{"relight render scene.json --rig rigs/evening.json --analysis analysis -o evening.exr",
        "evening.exr and evening.png, reusing the analysis folder"},
       {"relight render scene.json --rig rig.json -o relit.exr --exposure 1",
        "analyse, render, and a PNG one stop brighter"},
       {"relight render scene.json --rig dusk.json --analysis analysis --frames 1-120 -o out/dusk.####.exr",
        "an animated rig's frames: out/dusk.0001.exr ... out/dusk.0120.exr, each with its PNG"}}));
  run_when_parsed(*cmd, action, args, run_render);
}

}  // namespace relight::cli
