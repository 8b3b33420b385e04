// relight preview: the interactive engine, scripted. Moves the rig's first
// light around a circle (a turntable) through a relighting session, one
// frame per step as someone dragging it would see them, then lets the view
// converge, and reports how long each took.
#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <regex>

#include "cli/commands.h"
#include "core/error.h"
#include "core/statistics.h"
#include "io/json_text.h"
#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/scene_io.h"
#include "relight/session.h"

namespace relight::cli {

namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

double ms_since(Clock::time_point start) {
  return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// Step `step` of `steps` around a circle of radius `radius` about the light's
// start, in the plane square to `up`; a sun turns its direction about `up`.
Light turntable(const Light& start, const Vec3& up, float radius, int step, int steps) {
  const float angle = 2.0f * kPi * float(step) / float(steps);
  Light light = start;
  if (light.type == LightType::directional) {
    light.direction = Eigen::AngleAxisf(angle, up) * start.direction;
    return light;
  }
  Vec3 a, b;
  orthonormal_basis(up, a, b);
  light.position = start.position + radius * (std::cos(angle) * a + std::sin(angle) * b);
  return light;
}

void write_frame(const fs::path& folder, const std::string& name, const Image& image) {
  write_exr(folder / (name + ".exr"), image);
  write_png(folder / (name + ".png"), image);
}

// The OpenGL backend's shadow maps (docs/algorithms.md, section 8).
void add_shadow_map_options(CLI::App& cmd, ShadowMapOptions& o) {
  cmd.add_option("--shadow-map-size", o.size,
                 "gl: side of a spot's or area sample's shadow map (a point's cube faces: half)")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd.add_option("--sun-map-size", o.sun_size, "gl: side of each of the sun's cascaded shadow maps")
      ->check(CLI::Range(16, 16384))
      ->capture_default_str();
  cmd.add_option("--shadow-normal-offset", o.normal_offset,
                 "gl: shadow bias, texels the lookup moves off its surface along the normal")
      ->check(CLI::Range(0.0f, 16.0f))
      ->capture_default_str();
  cmd.add_option("--shadow-depth-offset", o.depth_offset, "gl: shadow bias, texels the lookup moves towards the light")
      ->check(CLI::Range(0.0f, 16.0f))
      ->capture_default_str();
  cmd.add_option("--shadow-pcf", o.pcf_radius, "gl: percentage-closer filter radius for soft lights, (2r+1)^2 taps")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  cmd.add_option("--shadow-samples", o.soft_samples, "gl: shadow maps per soft light (points over its extent)")
      ->check(CLI::Range(1, 256))
      ->capture_default_str();
}

struct PreviewArgs {
  std::string scene, rig, out, analysis, backend = "cpu", size;
  int frames = 60;
  float radius = 0.0f;
  AnalysisOptions options;
  ShadowMapOptions shadow_maps;
};

void run_preview(const PreviewArgs& args, Progress& progress) {
  const Rig rig = load_rig(args.rig);
  if (rig.lights.empty()) throw InputError(args.rig, "/lights", "preview moves the first light: the rig has none");
  SessionOptions options;
  options.backend = args.backend == "gl" ? Backend::gl : Backend::cpu;
  options.shadow_maps = args.shadow_maps;
  if (!args.size.empty()) {
    std::smatch m;
    if (!std::regex_match(args.size, m, std::regex(R"((\d{1,5})x(\d{1,5}))")) || std::stoi(m[1]) < 1 ||
        std::stoi(m[2]) < 1)
      throw InputError("--size", "", "expected WIDTHxHEIGHT, e.g. 1280x720, got '" + args.size + "'");
    options.width = std::stoi(m[1]);
    options.height = std::stoi(m[2]);
    expect_within_pixel_limit("--size", "a view", options.width, options.height);
  }
  options.final_render.paths_per_pixel = args.options.paths_per_pixel;
  options.final_render.max_bounces = args.options.max_bounces;
  const fs::path out(args.out);
  create_output_folder(out);

  const std::unique_ptr<AnalysedScene> analysed =
      load_analysed_scene(args.scene, args.analysis, args.options, progress);
  const Scene& scene = analysed->scene();
  RelightSession session(*analysed, rig, options);
  if (!session.backend_note().empty()) std::printf("%s\n", session.backend_note().c_str());
  std::printf("preview: %s backend, %dx%d; refining the starting view first...\n", to_string(session.backend()),
              session.view().width(), session.view().height());
  session.wait_until_converged();

  const Light start = rig.lights[0];
  const Vec3 up = scene.camera.spec().up.normalized();
  const float radius = args.radius > 0.0f ? args.radius : 0.25f * (start.position - scene.camera.spec().look_at).norm();
  std::vector<double> frame_ms;
  Frame first, last;
  for (int i = 0; i < args.frames; ++i) {
    if (progress.cancelled()) throw Cancelled();
    const auto t0 = Clock::now();
    const Frame frame = session.wait_for_edit(session.set_light(0, turntable(start, up, radius, i, args.frames)));
    frame_ms.push_back(ms_since(t0));
    (i == 0 ? first : last) = frame;
  }
  if (args.frames == 1) last = first;
  const auto released = Clock::now();
  const Frame converged = session.wait_until_converged();
  const double converge_ms = ms_since(released);

  const auto frame_name = [](int i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d", i);
    return std::string(name);
  };
  OutputBatch outputs;
  write_frame(out, frame_name(0), *first.image);
  if (args.frames > 1) write_frame(out, frame_name(args.frames - 1), *last.image);
  write_frame(out, "converged", *converged.image);
  nlohmann::json timing;
  timing["backend"] = to_string(session.backend());
  timing["width"] = session.view().width();
  timing["height"] = session.view().height();
  timing["frames"] = args.frames;
  timing["median_frame_ms"] = percentile(frame_ms, 0.5);
  timing["p95_frame_ms"] = percentile(frame_ms, 0.95);
  timing["converge_ms"] = converge_ms;
  timing["light"] = {{"name", start.name}, {"type", to_string(start.type)}, {"radius_m", radius}};
  timing["lights"] = rig.lights.size();
  write_text_atomically(out / "timing.json", json_text(timing));
  outputs.commit();
  std::printf("%d frames: median %.1f ms, p95 %.1f ms; converged %.0f ms after the last; written to %s\n", args.frames,
              double(timing["median_frame_ms"]), double(timing["p95_frame_ms"]), converge_ms, out.c_str());
}

}  // namespace

void add_preview_command(CLI::App& app, Action& action) {
  auto args = std::make_shared<PreviewArgs>();
  CLI::App* cmd = app.add_subcommand(
      "preview", "drag the rig's first light around a circle through the interactive engine, and time it");
  cmd->add_option("scene", args->scene, "scene.json")->required();
  cmd->add_option("--rig", args->rig, "rig.json: the lights; the first one moves")->required();
  cmd->add_option("-o,--out", args->out, "output folder: frame_NNNN.exr/.png, converged.exr/.png, timing.json")
      ->required();
  cmd->add_option("--backend", args->backend, "what draws a moving light: cpu (shadow rays) or gl (shadow maps)")
      ->check(CLI::IsMember({"cpu", "gl"}))
      ->capture_default_str();
  cmd->add_option("--size", args->size, "view size WxH (default: the photo's; then it converges to 'relight render')");
  cmd->add_option("--frames", args->frames, "steps around the circle")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_option("--radius", args->radius,
                  "circle radius in metres (default: a quarter of the light's distance to the camera's look_at)");
  cmd->add_option("--analysis", args->analysis,
                  "an analysis folder from 'relight analyze' to reuse (else the scene is analysed first)");
  add_sampling_options(*cmd, args->options);
  add_shadow_map_options(*cmd, args->shadow_maps);
  cmd->footer(help_footer(
      "Moves the rig's first light around a circle through the interactive relighting engine, writing each\n"
      "  frame, the converged image and timing.json (frame times).",
      {{"relight preview scene.json --rig rigs/evening.json --analysis analysis --size 1280x720 -o preview",
        "60 frames at 1280x720 on the CPU backend"},
       {"relight preview scene.json --rig rig.json --backend gl --frames 120 -o preview",
        "the OpenGL shadow-map backend"}}));
  run_when_parsed(*cmd, action, args, run_preview);
}

}  // namespace relight::cli
