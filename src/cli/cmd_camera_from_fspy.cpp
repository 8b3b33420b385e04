// relight camera-from-fspy: the camera block of scene.json from an fSpy
// camera match (project file or exported JSON).
#include <fmt/format.h>

#include <cstdio>

#include "cli/commands.h"
#include "core/error.h"
#include "io/json_text.h"
#include "io/atomic_file.h"
#include "io/fspy.h"
#include "io/json_reader.h"
#include "io/output_guard.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace {

// Replaces the camera of an existing scene.json, keeping everything else.
void update_scene_camera(const std::string& scene_path, const nlohmann::json& camera) {
  nlohmann::json scene = JsonReader::parse_file(scene_path);
  JsonReader(scene_path).expect_object(scene, "");
  allow_replacing_input(scene_path);  // rewriting it is what --scene is for
  scene["camera"] = camera;
  write_text_atomically(scene_path, json_text(scene));
}

struct CameraFromFspyArgs {
  std::string fspy, out, scene;
};

void run_camera_from_fspy(const CameraFromFspyArgs& args, Progress& progress) {
  const FspyCamera fspy = read_fspy_camera(args.fspy);
  const nlohmann::json camera = camera_to_json(fspy.camera);
  const auto& pp = fspy.camera.principal_point;
  const std::string summary = fmt::format("vfov {:.2f} deg, principal point ({:.3f}, {:.3f}), fSpy image {}x{}",
                                          fspy.camera.vfov_deg, pp.x(), pp.y(), fspy.image_width, fspy.image_height);
  if (!args.scene.empty()) {
    update_scene_camera(args.scene, camera);
    std::printf("camera of %s replaced: %s\n", args.scene.c_str(), summary.c_str());
  } else if (!args.out.empty()) {
    write_text_atomically(args.out, json_text(camera));
    std::printf("camera written to %s: %s\n", args.out.c_str(), summary.c_str());
  } else {
    std::printf("%s", json_text(camera).c_str());
  }
}

}  // namespace

void add_camera_from_fspy_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<CameraFromFspyArgs>();
  CLI::App* cmd = app.add_subcommand("camera-from-fspy", "the scene's camera from an fSpy camera match");
  cmd->add_option("fspy", args->fspy, "an fSpy project (.fspy) or the camera JSON fSpy exports")->required();
  auto* out = cmd->add_option("-o,--out", args->out, "write the camera block to this JSON file");
  cmd->add_option("--scene", args->scene, "replace the camera of this scene.json (its other keys are kept)")
      ->excludes(out);
  cmd->footer(help_footer(
      "Reads the camera fSpy matched to a photo (position, orientation, field of view, principal point) and\n"
      "  writes relight's camera block: to --out, into --scene, or to the terminal. fSpy's world axes become\n"
      "  the scene's: model the geometry in the same frame (as fSpy's Blender importer does). The photo must\n"
      "  have the aspect ratio of the image fSpy was given.",
      {{"relight camera-from-fspy kitchen.fspy --scene kitchen/scene.json", "set the scene's camera"},
       {"relight camera-from-fspy kitchen_camera.json -o camera.json",
        "from fSpy's File > Export > Camera parameters"}}));
  run_when_parsed(*cmd, action, args, run_camera_from_fspy);
}

}  // namespace relight::cli
