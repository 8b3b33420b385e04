// Writes the example scene examples/room/ with the program's own renderer:
// geometry.obj, photo.exr (path traced with the true albedo), scene.json,
// rigs/evening.json, and the truth to measure against: albedo_gt.exr,
// mask.exr and relit/evening.exr.
//   make_example OUTDIR [--width W --height H --spp N]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/scene_io.h"
#include "render/render_illumination.h"
#include "room_scene.h"

namespace fs = std::filesystem;
using namespace relight;

int main(int argc, char** argv) {
  CLI::App app{"make the example scene"};
  std::string out;
  int width = 320, height = 240, spp = 1024;
  app.add_option("outdir", out)->required();
  app.add_option("--width", width);
  app.add_option("--height", height);
  app.add_option("--spp", spp);
  CLI11_PARSE(app, argc, argv);

  fs::create_directories(fs::path(out) / "rigs");
  fs::create_directories(fs::path(out) / "relit");
  Scene scene = example::room_scene(width, height);
  scene.photo_path = fs::path(out) / "photo.exr";
  scene.geometry_path = fs::path(out) / "geometry.obj";
  const example::RoomAlbedo albedo = example::room_albedo();
  const RayScene rays(scene.mesh);
  const GBuffer gbuffer(scene.camera, rays, 16, 7, "example");
  Progress progress;

  const auto photo_under = [&](const std::vector<Light>& lights, float environment_scale) {
    const Lighting lighting = example::room_lighting(scene, lights, environment_scale);
    IntegratorOptions options;
    options.max_bounces = 8;
    const Integrator integrator(rays, lighting, &albedo, options);
    return synthesize_photo(gbuffer, scene.camera, integrator, albedo, spp, 99, progress);
  };
  write_exr(scene.photo_path, photo_under(scene.lights, 1.0f), ExrPrecision::half);
  const Rig evening = example::evening_rig();
  write_exr(fs::path(out) / "relit" / "evening.exr", photo_under(evening.lights, evening.environment_scale),
            ExrPrecision::half);

  write_exr(fs::path(out) / "albedo_gt.exr", example::room_albedo_image(gbuffer), ExrPrecision::half);
  write_exr_scalar(fs::path(out) / "mask.exr", gbuffer.coverage(), width, height);
  save_obj(scene.geometry_path, scene.mesh);
  save_rig(fs::path(out) / "rigs" / "evening.json", evening);
  write_text_atomically(fs::path(out) / "scene.json", scene_to_json(scene, out));
  std::printf("example scene written to %s\n", out.c_str());
  return 0;
}
