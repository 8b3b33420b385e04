// The relight command line: one file per subcommand, each registering itself
// on the CLI11 app; run() parses, dispatches and maps errors to exit codes
// (0 ok, 1 internal error, 2 bad input).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <initializer_list>
#include <memory>
#include <span>
#include <string>

#include "analysis/analyze.h"
#include "analysis/camera_registration.h"
#include "core/progress.h"
#include "render/ray_scene.h"

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
void add_hdr_merge_command(CLI::App& app, Action& action);
void add_probe_from_photo_command(CLI::App& app, Action& action);

// A loaded scene with its ray-tracing structure and G-buffer.
struct LoadedScene {
  Scene scene;
  std::unique_ptr<RayScene> rays;
  std::unique_ptr<GBuffer> gbuffer;
};
LoadedScene load_for_rendering(const std::string& scene_path, const AnalysisOptions& options, const Progress& progress);
// The same for a scene already loaded from scene_path.
LoadedScene prepare_for_rendering(Scene scene, const std::string& scene_path, const AnalysisOptions& options);

// A scene loaded for rendering with its analysis: read from analysis_folder
// (whose seed and sub-pixel samples then make the G-buffer) or, where that
// is empty, made now with `options`. Built in place and never moved: the
// ray-tracing structure refers to the scene's mesh.
struct AnalysedScene {
  AnalysedScene(const std::string& scene_path, const std::string& analysis_folder, AnalysisOptions options,
                Progress& progress);
  AnalysedScene(const AnalysedScene&) = delete;
  AnalysedScene& operator=(const AnalysedScene&) = delete;

  Analysis analysis;
  LoadedScene loaded;

 private:
  // The scene is read once: the analysis is checked against it, then it is rendered.
  AnalysedScene(Scene scene, const std::string& scene_path, const std::string& analysis_folder, AnalysisOptions options,
                Progress& progress);
};

// A man-page style --help footer: DESCRIPTION, EXAMPLES (each a command line
// and what it does), EXIT STATUS and where the full documentation is.
struct HelpExample {
  const char* command;
  const char* effect;
};
std::string help_footer(const char* description, std::initializer_list<HelpExample> examples);

// Registers the scene's camera to its photo (analysis/camera_registration.h)
// and prints what moved and how much the edge mismatch fell.
RegistrationResult register_and_report(Scene& scene, const RayScene& rays, const RegistrationOptions& options,
                                       Progress& progress);

// Options shared by analyze and render.
void add_sampling_options(CLI::App& cmd, AnalysisOptions& options);

int run(std::span<const std::string> args);

}  // namespace relight::cli
