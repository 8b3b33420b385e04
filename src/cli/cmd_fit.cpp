// relight fit: the principal lights' power and colour and the background,
// fitted so that the albedo shows no shadow edges (src/analysis/fit.h).
#include <cstdio>
#include <filesystem>

#include "analysis/fit.h"
#include "cli/commands.h"
#include "io/atomic_file.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace fs = std::filesystem;

void add_fit_command(CLI::App& app, Action& action) {
  struct Args {
    std::string scene, out;
    AnalysisOptions options;
  };
  auto args = std::make_shared<Args>();
  args->options.paths_per_pixel = FitOptions{}.paths_per_pixel;
  CLI::App* cmd = app.add_subcommand("fit", "fit the lights' power and colour and the background to the photo");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("-o,--out", args->out, "the fitted scene.json to write (paths rewritten to still resolve)")
      ->required();
  add_sampling_options(*cmd, args->options);
  cmd->footer(help_footer(
      "Lights a probe sees get the power the probe measures; the background and the other lights are fitted so\n"
      "  that the albedo does not change across shadow edges. Writes a complete scene.json.",
      {{"relight fit scene.json -o scene_fitted.json && relight analyze scene_fitted.json -o analysis",
        "fit the lights, then analyse with the fitted scene"}}));
  cmd->callback([&action, args] {
    action = [args](Progress& progress) {
      LoadedScene s = load_for_rendering(args->scene, args->options);
      FitOptions options;
      options.paths_per_pixel = args->options.paths_per_pixel;
      options.seed = args->options.seed;
      options.max_bounces = args->options.max_bounces;
      const FitResult fit = fit_lighting(s.scene, *s.rays, *s.gbuffer, options, progress);
      const fs::path out = fs::absolute(args->out);
      write_text_atomically(out, scene_to_json(fit.scene, out.parent_path()));
      for (const auto& l : fit.lights)
        std::printf("%-16s emission %.4g %.4g %.4g -> %.4g %.4g %.4g (%s)\n", l.name.c_str(), l.emission_before.x(),
                    l.emission_before.y(), l.emission_before.z(), l.emission_after.x(), l.emission_after.y(),
                    l.emission_after.z(), l.source.c_str());
      std::printf("%-16s %.4g %.4g %.4g -> %.4g %.4g %.4g (%s)\n", "background", fit.background_before.x(),
                  fit.background_before.y(), fit.background_before.z(), fit.background_after.x(),
                  fit.background_after.y(), fit.background_after.z(), fit.background_source.c_str());
      std::printf("%zu shadow-edge pixel pairs\n", fit.edge_pairs);
      std::printf("fitted scene written to %s\n", args->out.c_str());
    };
  });
}

}  // namespace relight::cli
