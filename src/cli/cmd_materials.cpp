// relight materials: which surfaces shine, estimated from the photo, written
// as scene.json's `materials` (src/analysis/material_estimation.h).
#include <cstdio>
#include <filesystem>
#include <map>

#include "analysis/material_estimation.h"
#include "analysis/strategy.h"
#include "analysis/view_checks.h"
#include "cli/commands.h"
#include "io/atomic_file.h"
#include "io/output_guard.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

struct MaterialsArgs {
  std::string scene, out;
  AnalysisOptions options;
  size_t min_pixels = MaterialEstimationOptions{}.min_pixels;
};

void run_materials(const MaterialsArgs& args, Progress& progress) {
  check_output_folder(args.out);
  Scene scene = load_scene(args.scene, progress);
  log_scene(scene, args.scene);
  check_output_is_not_an_input(fs::absolute(args.out));  // before the work, not after it
  // Written back as given: the camera and a grey card in the photo's own pixels.
  const Camera given_camera = scene.camera;
  const std::optional<AlbedoReference> given_reference = scene.reference;
  reduce_photo(scene, kEstimationPixels, "materials");
  LoadedScene s = prepare_for_analysis(std::move(scene), args.options, progress, CameraUse::for_analysis);
  require_named_objects(s.scene);
  warn_about_the_view(s.scene, *s.rays, *s.gbuffer);
  AnalysisOptions options = args.options;
  options.strategy = default_strategy(s.scene);
  const Analysis analysis = analyze(s.scene, *s.rays, *s.gbuffer, options, progress);
  MaterialEstimationOptions estimation;
  estimation.paths_per_pixel = args.options.paths_per_pixel;
  estimation.seed = args.options.seed;
  estimation.min_pixels = args.min_pixels;
  const std::vector<MaterialEstimate> estimates =
      estimate_materials(s.scene, *s.rays, *s.gbuffer, analysis, estimation, progress);
  for (const MaterialEstimate& m : estimates) std::printf("%s\n", describe_estimate(m).c_str());
  std::map<std::string, Gloss> materials = with_estimates(s.scene.materials, estimates);
  // The scene as given, with the materials: a camera the analysis
  // registered is its own business (relight register writes one).
  s.scene.camera = given_camera;
  s.scene.reference = given_reference;
  set_materials(s.scene, std::move(materials));
  const fs::path out = fs::absolute(args.out);
  write_text_atomically(out, scene_to_json(s.scene, out.parent_path()));
  std::printf("scene with its materials written to %s\n", args.out.c_str());
}

}  // namespace

void add_materials_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<MaterialsArgs>();
  CLI::App* cmd = app.add_subcommand("materials",
                                     "estimate which surfaces shine (roughness, specular) from the photo's highlights");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("-o,--out", args->out, "the scene.json to write, with `materials` (paths rewritten to still resolve)")
      ->required();
  cmd->add_option("--min-pixels", args->min_pixels, "leave objects the photo shows by fewer whole pixels as they are")
      ->check(CLI::Range(size_t(16), size_t(1) << 30))
      ->capture_default_str();
  add_sampling_options(*cmd, args->options);
  cmd->footer(help_footer(
      "Analyses the scene with its surfaces matte (those `materials` names keep theirs), then predicts the\n"
      "  highlights its lights and environment would make on each object at roughnesses 0.05-0.7 and keeps the\n"
      "  one whose shape the photo shows, scaled to it. An object stays matte where no highlight explains 10 % of\n"
      "  its shading's fine variation, or where its highlights are brighter than a dielectric's (a metal). A\n"
      "  coloured object none explains is tried for a broad sheen (its untinted change over a tenth of the view),\n"
      "  kept where it stands 4.5 standard errors clear of none. Objects made wholly of a material no other\n"
      "  surface has are estimated together, under the material's name. Writes a complete scene.json; analyse\n"
      "  that one. docs/algorithms.md section 13.",
      {{"relight materials scene.json -o scene_materials.json && relight analyze scene_materials.json -o analysis",
        "find the glossy surfaces, then analyse with their highlights taken off the photo"}}));
  run_when_parsed(*cmd, action, args, run_materials);
}

}  // namespace relight::cli
