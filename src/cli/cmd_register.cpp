// relight register: the camera moved, turned and zoomed so that the
// geometry's edges meet the photo's (src/analysis/camera_registration.h).
#include <cstdio>
#include <filesystem>

#include "analysis/camera_registration.h"
#include "cli/commands.h"
#include "io/atomic_file.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace fs = std::filesystem;

RegistrationResult register_and_report(Scene& scene, const RayScene& rays, const RegistrationOptions& options,
                                       Progress& progress) {
  const RegistrationResult r = register_camera(scene, rays, options, progress);
  for (const std::string& line : describe_registration(r, scene.camera.width(), scene.camera.height()))
    std::printf("%s\n", line.c_str());
  return r;
}

namespace {

struct RegisterArgs {
  std::string scene, out;
  RegistrationOptions options;
  bool fixed_position = false, pinhole = false;
};

void run_register(const RegisterArgs& args, Progress& progress) {
  AnalysisOptions load;
  load.gbuffer_samples = 1;
  LoadedScene s = load_for_analysis(args.scene, load, progress);
  RegistrationOptions options = args.options;
  options.refine_position = !args.fixed_position;
  options.refine_distortion = !args.pinhole;
  register_and_report(s.scene, *s.rays, options, progress);
  const fs::path out = fs::absolute(args.out);
  write_text_atomically(out, scene_to_json(s.scene, out.parent_path()));
  std::printf("registered scene written to %s\n", args.out.c_str());
}

}  // namespace

void add_register_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<RegisterArgs>();
  CLI::App* cmd = app.add_subcommand("register", "refine the camera so that the geometry's edges meet the photo's");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("-o,--out", args->out, "the registered scene.json to write (paths rewritten to still resolve)")
      ->required();
  cmd->add_option("--max-turn", args->options.max_turn_deg, "refuse to turn the camera more than this (degrees)")
      ->check(CLI::Range(0.0f, 45.0f))
      ->capture_default_str();
  cmd->add_option("--max-fov-change", args->options.max_fov_change,
                  "refuse to change vfov_deg by more than this fraction of it")
      ->check(CLI::Range(0.0f, 0.5f))
      ->capture_default_str();
  cmd->add_option("--max-shift", args->options.max_principal_point_shift,
                  "refuse to move the principal point more than this fraction of the photo's width")
      ->check(CLI::Range(0.0f, 0.5f))
      ->capture_default_str();
  cmd->add_option("--max-move", args->options.max_move_m, "refuse to move the camera more than this (m)")
      ->check(CLI::Range(0.0f, 10.0f))
      ->capture_default_str();
  cmd->add_flag("--fixed-position", args->fixed_position,
                "keep the camera's position; refine only its orientation, vfov_deg, principal point and distortion");
  cmd->add_flag("--pinhole", args->pinhole, "keep the lens's distortion as given (none unless camera.distortion says)");
  cmd->footer(help_footer(
      "The photo's edges (Canny on log luminance) and the geometry's (silhouettes, depth steps, creases) are\n"
      "  matched coarse to fine: the camera's orientation, position, vfov_deg, principal point and the lens's\n"
      "  radial distortion k1 move so that the geometry's edges fall on the photo's. A camera that would have to move "
      "further than the --max-*\n"
      "  limits is refused (exit 2, nothing written): the match is wrong, not small. Writes a complete scene.json.",
      {{"relight register scene.json -o scene_registered.json", "refine the camera of a hand-made camera match"},
       {"relight register scene.json --fixed-position -o scene_registered.json",
        "keep the camera where it is; only turn and zoom it"}}));
  run_when_parsed(*cmd, action, args, run_register);
}

}  // namespace relight::cli
