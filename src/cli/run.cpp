#include "cli/run.h"

#include <spdlog/pattern_formatter.h>
#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <string_view>

#include "cli/commands.h"
#include "core/error.h"
#include "io/atomic_file.h"
#include "io/frame_files.h"
#include "io/image_io.h"
#include "io/mesh_io.h"
#include "io/output_guard.h"
#include "io/response_curve.h"
#include "io/scene_folder_reads.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace {
Progress* g_progress = nullptr;
void on_interrupt(int) {
  if (g_progress) g_progress->cancel();
}

// Text printed on the terminal holds names and keys from files (scene.json
// is anyone's): line breaks and tabs become spaces, so that an error is one
// line even where a library's message spans several, and every other control
// character (the escape sequences that recolour, retitle or clear a terminal;
// backspaces) is shown as \xHH, or \u00HH for a C1 control in UTF-8.
std::string printable(std::string_view text) {
  std::string out;
  for (size_t i = 0; i < text.size(); ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == '\n' || c == '\r' || c == '\t') {
      out += ' ';
    } else if (c < 0x20 || c == 0x7f) {
      out += fmt::format("\\x{:02x}", c);
    } else if (c == 0xc2 && i + 1 < text.size() && static_cast<unsigned char>(text[i + 1]) < 0xa0 &&
               static_cast<unsigned char>(text[i + 1]) >= 0x80) {
      out += fmt::format("\\u{:04x}", static_cast<unsigned char>(text[++i]));
    } else {
      out += char(c);
    }
  }
  return out;
}

// The `%*` of the log pattern: the message, printable().
class PrintableMessage : public spdlog::custom_flag_formatter {
 public:
  void format(const spdlog::details::log_msg& msg, const std::tm&, spdlog::memory_buf_t& dest) override {
    const std::string text = printable(std::string_view(msg.payload.data(), msg.payload.size()));
    dest.append(text.data(), text.data() + text.size());
  }
  std::unique_ptr<custom_flag_formatter> clone() const override { return std::make_unique<PrintableMessage>(); }
};
}  // namespace

void log_scene(const Scene& scene, const std::string& scene_path) {
  spdlog::info("{}: photo {}x{}, {} triangles, {} lights, {} probes", scene_path, scene.photo.width, scene.photo.height,
               scene.mesh.triangles.size(), scene.lights.size(), scene.probes.size());
}

LoadedScene load_for_analysis(const std::string& scene_path, const AnalysisOptions& options, Progress& progress,
                              CameraUse camera) {
  Scene scene = load_scene(scene_path, progress);
  log_scene(scene, scene_path);
  return prepare_for_analysis(std::move(scene), options, progress, camera);
}

LoadedScene prepare_for_analysis(Scene&& scene, const AnalysisOptions& options, Progress& progress, CameraUse camera) {
  LoadedScene s;
  s.scene = std::move(scene);
  if (options.preview) reduce_for_preview(s.scene);
  s.rays = std::make_unique<RayScene>(s.scene.mesh);
  if (camera == CameraUse::for_analysis) s.registered_camera = camera_for_analysis(s.scene, *s.rays, options, progress);
  s.gbuffer = std::make_unique<GBuffer>(scene_gbuffer(s.scene, *s.rays, options));
  return s;
}

FrameRange frames_option(const std::string& text) {
  const std::optional<FrameRange> frames = parse_frame_range(text);
  if (!frames) throw InputError("--frames", "", "expected a frame (12) or a range (1-120), got '" + text + "'");
  return *frames;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

std::string help_footer(const char* description, std::initializer_list<HelpExample> examples) {
  std::string text = "DESCRIPTION\n  " + std::string(description) + "\n\nEXAMPLES\n";
  for (const HelpExample& e : examples) text += "  " + std::string(e.command) + "\n      " + e.effect + "\n";
  text +=
      "\nEXIT STATUS\n  0 done; 2 bad input (one line naming the file and the problem); 1 internal error;\n"
      "  3 work not finished (farm-check: frames missing); 130 interrupted (nothing half written)\n\n"
      "SEE ALSO\n  docs/commands.md, docs/formats.md (installed in share/doc/relight)";
  return text;
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

void add_keep_vignetting_flag(CLI::App& cmd, AnalysisOptions& o) {
  cmd.add_flag("--keep-vignetting", o.keep_vignetting,
               "leave the photo's vignetting in it; by default a darkening towards its corners that the probes "
               "show is not the surfaces' (5 % or more, clear of the noise) is divided out first");
}

int run(std::span<const std::string> args) {
  CLI::App app{"relight: relight a photograph physically (analyse, then render new lighting)", "relight"};
  app.set_version_flag("--version", "relight " RELIGHT_VERSION);
  app.require_subcommand(1);
  app.footer(help_footer(
      "relight works out the light a photograph was taken under from the scene's geometry, camera, lights and\n"
      "  probes, removes it (leaving the albedo) and renders the photo under new lights. 'relight COMMAND --help'\n"
      "  describes each command.",
      {{"relight analyze scene.json -o analysis", "recover the albedo"},
       {"relight rig scene.json -o rig.json", "start a lighting design from the scene's lights"},
       {"relight render scene.json --rig rig.json --analysis analysis -o relit.exr", "re-light the photo"}}));
  bool verbose = false;
  app.add_flag("-v,--verbose", verbose, "print what each step does");
  int64_t max_pixels = default_max_image_pixels();
  app.add_option("--max-pixels", max_pixels,
                 "refuse photos and probes of more pixels than this; memory grows with the photo's size, and "
                 "the default is the largest photo whose analysis fits in half of this machine's memory "
                 "(docs/reliability.md)")
      ->envname("RELIGHT_MAX_PIXELS")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  std::string response;
  app.add_option("--response", response,
                 "linearise 8/16-bit photos and probes through this tone curve (a text file of `encoded linear` rows, "
                 "docs/formats.md) instead of sRGB");
  bool repair_mesh = false;
  app.add_flag("--repair-mesh", repair_mesh,
               "drop the geometry's degenerate (zero-area) triangles with a warning instead of refusing it")
      ->envname("RELIGHT_REPAIR_MESH");
  bool confine = false;
  app.add_flag("--confine-to-scene-folder", confine,
               "refuse a scene whose files (photo, geometry, probes, a glTF's buffers and images, an OBJ's mtllib) lie "
               "outside the scene.json's folder, instead of warning; for scenes from others")
      ->envname("RELIGHT_CONFINE_TO_SCENE_FOLDER");
  app.fallthrough();  // the global options may follow the subcommand
  Action action;
  add_analyze_command(app, action);
  add_render_command(app, action);
  add_rig_command(app, action);
  add_compare_command(app, action);
  add_preview_command(app, action);
  add_fit_command(app, action);
  add_mesh_command(app, action);
  add_camera_from_fspy_command(app, action);
  add_register_command(app, action);
  add_materials_command(app, action);
  add_hdr_merge_command(app, action);
  add_probe_from_photo_command(app, action);
  add_farm_command(app, action);
  bool force = false;
  for (const char* writer : {"analyze", "render", "rig", "preview", "fit", "mesh", "camera-from-fspy", "register",
                             "materials", "hdr-merge", "probe-from-photo"})
    app.get_subcommand(writer)->add_flag(
        "--force", force,
        "replace an output file that is read-only (keeping its mode); analyze: also write into a folder holding "
        "images of its names but no analysis");

  std::vector<std::string> reversed(args.rbegin(), args.rend() - 1);  // CLI11 wants them reversed, without argv[0]
  try {
    app.parse(reversed);
  } catch (const CLI::ParseError& e) {
    return app.exit(e) == 0 ? 0 : 2;
  }
  set_max_image_pixels(max_pixels);
  set_ldr_response_file(response);
  set_repair_meshes(repair_mesh);
  set_force_outputs(force);
  set_confine_to_scene_folder(confine);
  // Warnings go to stderr with the errors; stdout carries only the results.
  static const auto log_to_stderr =
      std::make_shared<spdlog::logger>("relight", std::make_shared<spdlog::sinks::stderr_color_sink_mt>());
  spdlog::set_default_logger(log_to_stderr);
  auto formatter = std::make_unique<spdlog::pattern_formatter>();
  formatter->add_flag<PrintableMessage>('*').set_pattern("relight: %^%l%$: %*");
  spdlog::set_formatter(std::move(formatter));
  spdlog::set_level(verbose ? spdlog::level::info : spdlog::level::warn);

  Progress progress;
  g_progress = &progress;
  std::signal(SIGINT, on_interrupt);
  struct ForgetProgress {
    ~ForgetProgress() { g_progress = nullptr; }  // a later Ctrl-C must not reach a dead Progress
  } forget_progress;
  try {
    const OutputGuard no_input_replaced;
    action(progress);
    return 0;
  } catch (const InputError& e) {
    std::fprintf(stderr, "\nrelight: error: %s\n", printable(e.what()).c_str());
    return 2;
  } catch (const Unfinished& e) {
    std::fprintf(stderr, "relight: %s\n", printable(e.what()).c_str());
    return 3;
  } catch (const Cancelled&) {
    std::fprintf(stderr, "\nrelight: cancelled; nothing was written\n");
    return 130;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "\nrelight: internal error: %s\n", printable(e.what()).c_str());
    return 1;
  }
}

}  // namespace relight::cli
