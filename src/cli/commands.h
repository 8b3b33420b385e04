// The relight command line: one file per subcommand, each registering itself
// on the CLI11 app; run() (run.h) parses, dispatches and maps errors to exit codes
// (0 ok, 1 internal error, 2 bad input).
#pragma once

#include <CLI/CLI.hpp>
#include <chrono>
#include <functional>
#include <initializer_list>
#include <memory>
#include <string>

#include "analysis/analysed_scene.h"
#include "analysis/camera_registration.h"
#include "core/progress.h"
#include "render/ray_scene.h"
#include "scene/animation.h"

namespace relight::cli {

// The action a parsed subcommand runs.
using Action = std::function<void(Progress&)>;

// Makes run(*args, progress) the action once `cmd` has been parsed into *args.
template <class Args>
void run_when_parsed(CLI::App& cmd, Action& action, std::shared_ptr<Args> args, void (*run)(const Args&, Progress&)) {
  cmd.callback([&action, args, run] { action = [args, run](Progress& progress) { run(*args, progress); }; });
}

void add_analyze_command(CLI::App& app, Action& action);
void add_render_command(CLI::App& app, Action& action);
void add_rig_command(CLI::App& app, Action& action);
void add_compare_command(CLI::App& app, Action& action);
void add_preview_command(CLI::App& app, Action& action);
void add_fit_command(CLI::App& app, Action& action);
void add_mesh_command(CLI::App& app, Action& action);
void add_camera_from_fspy_command(CLI::App& app, Action& action);
void add_register_command(CLI::App& app, Action& action);
void add_materials_command(CLI::App& app, Action& action);
void add_hdr_merge_command(CLI::App& app, Action& action);
void add_probe_from_photo_command(CLI::App& app, Action& action);
void add_farm_command(CLI::App& app, Action& action);

// Work found not finished (relight farm-check: frames missing): exit status 3.
class Unfinished : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A scene to analyse, fit or register: loaded, with its ray-tracing
// structure and the G-buffer `options` make (a scene with its analysis, to
// relight: AnalysedScene). With CameraUse::for_analysis, the camera is
// first registered to the photo where off and options allow
// (camera_for_analysis, analyze.h).
enum class CameraUse { as_given, for_analysis };
struct LoadedScene {
  Scene scene;
  std::unique_ptr<RayScene> rays;
  std::unique_ptr<GBuffer> gbuffer;
  std::optional<CameraSpec> registered_camera;
};
LoadedScene load_for_analysis(const std::string& scene_path, const AnalysisOptions& options, Progress& progress,
                              CameraUse camera = CameraUse::as_given);
// The same for a scene already loaded (a shot's frame).
LoadedScene prepare_for_analysis(Scene&& scene, const AnalysisOptions& options, Progress& progress,
                                 CameraUse camera = CameraUse::as_given);
// Logs what scene_path holds: photo size, triangles, lights, probes.
void log_scene(const Scene& scene, const std::string& scene_path);

// scene.json loaded with its analysis: read from analysis_folder or, where
// that is empty, made now with `options` and the strategy the scene's data
// suggests.
std::unique_ptr<AnalysedScene> load_analysed_scene(const std::string& scene_path, const std::string& analysis_folder,
                                                   AnalysisOptions options, Progress& progress);
// The same for a scene already loaded.
std::unique_ptr<AnalysedScene> analysed_scene(Scene&& scene, const std::string& analysis_folder,
                                              AnalysisOptions options, Progress& progress);

// A man-page style --help footer: DESCRIPTION, EXAMPLES (each a command line
// and what it does), EXIT STATUS and where the full documentation is.
struct HelpExample {
  const char* command;
  const char* effect;
};
std::string help_footer(const char* description, std::initializer_list<HelpExample> examples);

// The --frames option's range ("12" or "1-120"); InputError naming the
// option where it is neither.
FrameRange frames_option(const std::string& text);

// Seconds from `start` to now.
double seconds_since(std::chrono::steady_clock::time_point start);

// Registers the scene's camera to its photo (analysis/camera_registration.h)
// and prints what moved and how much the edge mismatch fell.
RegistrationResult register_and_report(Scene& scene, const RayScene& rays, const RegistrationOptions& options,
                                       Progress& progress);

// Options shared by analyze and render.
void add_sampling_options(CLI::App& cmd, AnalysisOptions& options);
// --keep-vignetting, shared by analyze and fit.
void add_keep_vignetting_flag(CLI::App& cmd, AnalysisOptions& options);

}  // namespace relight::cli
