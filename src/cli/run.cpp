#include <spdlog/spdlog.h>

#include <csignal>
#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace {
Progress* g_progress = nullptr;
void on_interrupt(int) {
  if (g_progress) g_progress->cancel();
}
}  // namespace

LoadedScene load_for_rendering(const std::string& scene_path, const AnalysisOptions& options) {
  LoadedScene s;
  s.scene = load_scene(scene_path);
  spdlog::info("{}: photo {}x{}, {} triangles, {} lights, {} probes", scene_path, s.scene.photo.width,
               s.scene.photo.height, s.scene.mesh.triangles.size(), s.scene.lights.size(), s.scene.probes.size());
  s.rays = std::make_unique<RayScene>(s.scene.mesh);
  s.gbuffer = std::make_unique<GBuffer>(scene_gbuffer(s.scene, *s.rays, options));
  return s;
}

void add_sampling_options(CLI::App& cmd, AnalysisOptions& o) {
  cmd.add_option("--spp", o.paths_per_pixel, "light paths per pixel (more: less noise, slower)")
      ->check(CLI::Range(1, 1 << 16))
      ->capture_default_str();
  cmd.add_option("--seed", o.seed, "random seed; the same seed gives the same image")->capture_default_str();
  cmd.add_option("--bounces", o.max_bounces, "diffuse bounces of interreflection")
      ->check(CLI::Range(0, 64))
      ->capture_default_str();
}

int run(std::span<const std::string> args) {
  CLI::App app{"relight: relight a photograph physically (analyse, then render new lighting)", "relight"};
  app.set_version_flag("--version", "relight " RELIGHT_VERSION);
  app.require_subcommand(1);
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "print what each step does");
  Action action;
  add_analyze_command(app, action);
  add_render_command(app, action);
  add_rig_command(app, action);
  add_compare_command(app, action);
  add_fit_command(app, action);

  std::vector<std::string> reversed(args.rbegin(), args.rend() - 1);  // CLI11 wants them reversed, without argv[0]
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  spdlog::set_pattern("relight: %^%l%$: %v");
  spdlog::set_level(verbose ? spdlog::level::info : spdlog::level::warn);

  Progress progress;
  g_progress = &progress;
  std::signal(SIGINT, on_interrupt);
  try {
    action(progress);
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "\nrelight: error: %s\n", e.what());
    return 2;
  } catch (const Cancelled&) {
    std::fprintf(stderr, "\nrelight: cancelled; nothing was written\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\nrelight: internal error: %s\n", e.what());
    return 1;
  }
}

}  // namespace relight::cli
