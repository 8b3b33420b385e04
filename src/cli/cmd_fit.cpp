// relight fit: the principal lights' power and colour and the background,
// fitted so that the albedo shows no shadow edges (src/analysis/fit.h).
#include <cstdio>
#include <filesystem>

#include "analysis/fit.h"
#include "analysis/view_checks.h"
#include "cli/commands.h"
#include "io/atomic_file.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

struct FitArgs {
  std::string scene, out;
  AnalysisOptions options;
  bool refine_placement = false, register_camera = false;
};

void run_fit(const FitArgs& args, Progress& progress) {
  LoadedScene s = load_for_analysis(args.scene, args.options, progress);
  if (args.register_camera) {
    register_and_report(s.scene, *s.rays, RegistrationOptions{}, progress);
    s.gbuffer = std::make_unique<GBuffer>(scene_gbuffer(s.scene, *s.rays, args.options));
  }
  warn_about_the_view(s.scene, *s.rays, *s.gbuffer);
  FitOptions options;
  options.paths_per_pixel = args.options.paths_per_pixel;
  options.seed = args.options.seed;
  options.max_bounces = args.options.max_bounces;
  options.refine_placement = args.refine_placement;
  options.keep_vignetting = args.options.keep_vignetting;
  const FitResult fit = fit_lighting(s.scene, *s.rays, *s.gbuffer, options, progress);
  const fs::path out = fs::absolute(args.out);
  write_text_atomically(out, scene_to_json(fit.scene, out.parent_path()));
  for (const std::string& line : describe_fit(fit)) std::printf("%s\n", line.c_str());
  std::printf("fitted scene written to %s\n", args.out.c_str());
}

}  // namespace

void add_fit_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<FitArgs>();
  args->options.paths_per_pixel = FitOptions{}.paths_per_pixel;
  CLI::App* cmd = app.add_subcommand("fit", "fit the lights' power and colour and the background to the photo");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("-o,--out", args->out, "the fitted scene.json to write (paths rewritten to still resolve)")
      ->required();
  cmd->add_flag("--refine-placement", args->refine_placement,
                "then move and turn each light (a point: move; the sun: turn) to where its shadows fall in the photo");
  cmd->add_flag("--register", args->register_camera,
                "first register the camera to the photo's edges, as relight register does (default limits)");
  add_sampling_options(*cmd, args->options);
  add_keep_vignetting_flag(*cmd, args->options);
  cmd->footer(help_footer(
      "Lights a probe sees get the power the probe measures; the background and the other lights are fitted so\n"
      "  that the albedo does not change across shadow edges. With --refine-placement, lights up to ~25 cm and\n"
      "  ~4 degrees from where they were are moved and turned to match their shadows. Writes a complete scene.json.",
      {{"relight fit scene.json -o scene_fitted.json && relight analyze scene_fitted.json -o analysis",
        "fit the lights, then analyse with the fitted scene"},
       {"relight fit scene.json --refine-placement -o scene_fitted.json",
        "also correct the lights' positions and directions from the shadows"}}));
  run_when_parsed(*cmd, action, args, run_fit);
}

}  // namespace relight::cli
