// relight render: the photo under a new rig.
#include <spdlog/spdlog.h>

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "cli/commands.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_io.h"
#include "relight/render_rig.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

struct RenderArgs {
  std::string scene, rig, out, analysis;
  AnalysisOptions options;
  const CLI::Option* spp = nullptr;  // given or not
  float exposure = 0.0f;
};

void run_render(const RenderArgs& args, Progress& progress) {
  const auto start = std::chrono::steady_clock::now();
  const Rig rig = load_rig(args.rig);
  fs::path out(args.out);
  if (out.extension() != ".exr") out += ".exr";
  const std::unique_ptr<AnalysedScene> analysed =
      load_analysed_scene(args.scene, args.analysis, args.options, progress);
  RenderOptions render_options;
  // By default the analysis's paths: with its seed, the render's noise then
  // follows the analysis's, and the scene's own lights give back the photo.
  render_options.paths_per_pixel =
      args.spp->count() ? args.options.paths_per_pixel : analysed->analysis().options.paths_per_pixel;
  render_options.max_bounces = args.options.max_bounces;
  const Image image = render_rig(*analysed, rig, render_options, progress);
  fs::path png = out;
  png.replace_extension(".png");
  OutputBatch pair;  // the EXR and the PNG appear together
  write_exr(out, image);
  write_png(png, image, args.exposure);
  pair.commit();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::printf("re-lit image written to %s and %s in %.1f s\n", out.c_str(), png.c_str(), secs);
}

}  // namespace

void add_render_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "render the photo under a new lighting design (rig.json)");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("--rig", args->rig, "rig.json: the new lights")->required();
  cmd->add_option("-o,--out", args->out, "output EXR; a tone-mapped PNG is written beside it")->required();
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
        "analyse, render, and a PNG one stop brighter"}}));
  run_when_parsed(*cmd, action, args, run_render);
}

}  // namespace relight::cli
