// relight mesh: the scene mesh refined along the photo's shadow edges
// (thesis chapter 4) — mesh.obj, a picture of its edges over the photo
// (mesh.png) and mesh.json with the counts and the time.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "cli/commands.h"
#include "core/error.h"
#include "io/json_text.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/scene_io.h"
#include "mesh/mesh_picture.h"
#include "mesh/refine.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

const std::map<std::string, SplitCriterion> kCriteria = {{"line-fit", SplitCriterion::line_fit},
                                                         {"end-points", SplitCriterion::compare_end_points},
                                                         {"std-dev", SplitCriterion::standard_deviation}};
const std::map<std::string, FlipTest> kFlipTests = {{"side", FlipTest::side_of_edge},
                                                    {"segment", FlipTest::segment_intersection}};

// How closely the mesh's edges follow the shadow edges of the true albedo.
nlohmann::json shadow_edge_figures(const std::string& albedo_path, const std::string& mask_path, const Scene& scene,
                                   const GBuffer& gbuffer, const std::vector<uint8_t>& edges) {
  const Image albedo = read_image(albedo_path);
  if (albedo.width != scene.photo.width || albedo.height != scene.photo.height)
    throw InputError(albedo_path, "", "differs in size from the photo");
  std::vector<float> mask(scene.photo.size(), 1.0f);
  if (!mask_path.empty()) {
    int w, h;
    mask = read_scalar_image(mask_path, w, h);
    if (w != scene.photo.width || h != scene.photo.height)
      throw InputError(mask_path, "", "differs in size from the photo");
  }
  const std::vector<uint8_t> shadow = shadow_edge_pixels(scene.photo, albedo, mask, gbuffer);
  size_t count = 0;
  for (uint8_t s : shadow) count += s;
  return {
      {"shadow_edge_pixels", count},
      {"shadow_edge_share_within_1_5_px", share_within_1_5_px(shadow, edges, scene.photo.width, scene.photo.height)}};
}

struct MeshArgs {
  std::string scene, out, criterion = "line-fit", flip_test = "side", albedo_gt, mask;
  RefineOptions options;
};

void run_mesh(const MeshArgs& args, Progress& progress) {
  RefineOptions options = args.options;
  options.subdivision.criterion = kCriteria.at(args.criterion);
  options.relax.flip_test = kFlipTests.at(args.flip_test);
  const Scene scene = load_scene(args.scene, progress);
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 1, 1, args.scene);
  const PhotoSamples photo = photo_samples(scene.photo, gbuffer);
  RefineReport report;
  const ConnectivityMesh mesh = refine_mesh_for_photo(scene.mesh, scene.camera, photo, options, report);
  const std::vector<uint8_t> edges = visible_edge_pixels(mesh, scene.camera, photo);

  nlohmann::json j = {{"triangles_input", report.triangles_input},
                      {"triangles_in_view", report.triangles_clipped},
                      {"triangles", mesh.triangles().size()},
                      {"vertices", mesh.vertices().size()},
                      {"edges", mesh.edges().size()},
                      {"edges_split_clipping", report.clip.edges_split},
                      {"long_edges_split", report.long_edges_split},
                      {"edges_tested", report.subdivision.edges_tested},
                      {"edges_split", report.subdivision.edges_split},
                      {"vertices_moved", report.relax.vertices_moved},
                      {"moves_refused", report.relax.moves_refused},
                      {"welded_vertices", report.cleanup.welded_vertices},
                      {"degenerate_triangles", report.cleanup.degenerate_triangles},
                      {"non_manifold_edges", report.cleanup.non_manifold_edges},
                      {"seconds", report.seconds},
                      {"options",
                       {{"criterion", args.criterion},
                        {"threshold", options.subdivision.threshold},
                        {"min_edge_px", options.subdivision.min_edge_px},
                        {"relax", options.relax.iterations},
                        {"flip_test", args.flip_test}}}};
  // Every input is read before anything is written.
  if (!args.albedo_gt.empty()) j.update(shadow_edge_figures(args.albedo_gt, args.mask, scene, gbuffer, edges));

  const fs::path out = args.out;
  create_output_folder(out);
  OutputBatch outputs;
  save_obj(out / "mesh.obj", mesh.to_triangle_mesh());
  write_png(out / "mesh.png", draw_edges_over_photo(scene.photo, edges));
  write_text_atomically(out / "mesh.json", json_text(j));
  outputs.commit();
  std::printf("mesh: %zu triangles in view -> %zu (%zu edges split, %zu vertices moved) in %.3f s, written to %s\n",
              report.triangles_clipped, mesh.triangles().size(), report.subdivision.edges_split,
              report.relax.vertices_moved, report.seconds, args.out.c_str());
  if (j.contains("shadow_edge_share_within_1_5_px"))
    std::printf("shadow-edge pixels within 1.5 px of a mesh edge: %.1f %% of %zu\n",
                100.0 * j["shadow_edge_share_within_1_5_px"].get<double>(), j["shadow_edge_pixels"].get<size_t>());
}

}  // namespace

void add_mesh_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<MeshArgs>();
  CLI::App* cmd = app.add_subcommand("mesh", "refine the scene mesh along the photo's shadow edges (thesis ch. 4)");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("-o,--out", args->out, "output folder (created)")->required();
  cmd->add_option("--criterion", args->criterion,
                  "when an edge crosses a shadow edge: line-fit (least squares, split at the largest error), "
                  "end-points (compare the ends) or std-dev (standard deviation); the last two split in the middle")
      ->check(CLI::IsMember({"line-fit", "end-points", "std-dev"}))
      ->capture_default_str();
  cmd->add_option("--threshold", args->options.subdivision.threshold,
                  "split when the error exceeds this fraction of the edge's mean intensity")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--min-edge", args->options.subdivision.min_edge_px,
                  "no split nearer than this many pixels to an edge's end")
      ->check(CLI::Range(2.0f, 1.0e4f))
      ->capture_default_str();
  cmd->add_option("--max-edge", args->options.max_edge_px,
                  "first split every edge longer than this many pixels (0: none; radiosity uses 24)")
      ->check(CLI::Range(0.0f, 1.0e4f))
      ->capture_default_str();
  cmd->add_option("--relax", args->options.relax.iterations, "relaxation passes (0: none)")
      ->check(CLI::Range(0, 100))
      ->capture_default_str();
  cmd->add_option("--flip-test", args->flip_test,
                  "test that refuses relaxation moves: side (of edge) or segment (intersection)")
      ->check(CLI::IsMember({"side", "segment"}))
      ->capture_default_str();
  cmd->add_option(
      "--albedo-gt", args->albedo_gt,
      "the true albedo: mesh.json then reports the share of shadow-edge pixels within 1.5 px of a mesh edge");
  cmd->add_option("--mask", args->mask, "with --albedo-gt: only pixels where this mask is 1 count");
  cmd->footer(help_footer(
      "Refines the scene's mesh along the photo's shadow edges (thesis chapter 4): clips it to the view,\n"
      "  splits edges where the photo along them is not a straight ramp, then moves vertices onto the edges.",
      {{"relight mesh scenes/outdoor/scene.json -o out/mesh", "writes out/mesh/{mesh.obj, mesh.png, mesh.json}"},
       {"relight mesh scene.json -o out/mesh --albedo-gt albedo_gt.exr --mask mask.exr",
        "also reports how many shadow-edge pixels lie near a mesh edge"}}));
  run_when_parsed(*cmd, action, args, run_mesh);
}

}  // namespace relight::cli
