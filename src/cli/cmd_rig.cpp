// relight rig: a rig.json holding the scene's own lights, to start a design from.
#include <cstdio>

#include "cli/commands.h"
#include "io/scene_io.h"
#include "relight/render_rig.h"

namespace relight::cli {

namespace {

struct RigArgs {
  std::string scene, out;
};

void run_rig(const RigArgs& args, Progress& progress) {
  save_rig(args.out, rig_from_scene(load_scene(args.scene, progress)));
  std::printf("rig written to %s\n", args.out.c_str());
}

}  // namespace

void add_rig_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<RigArgs>();
  CLI::App* cmd = app.add_subcommand("rig", "write a rig.json with the scene's own lights, to edit");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("-o,--out", args->out, "rig.json to write")->required();
  cmd->footer(help_footer(
      "Writes a rig.json holding the scene's own lights and environment_scale 1, the starting point of a new\n"
      "  lighting design; rendering it unchanged gives back the photo.",
      {{"relight rig scene.json -o my_rig.json", "my_rig.json with the scene's lights, to edit"}}));
  run_when_parsed(*cmd, action, args, run_rig);
}

}  // namespace relight::cli
