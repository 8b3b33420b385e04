// The scene and analysis that render and preview work from.
#include "analysis/analysis_folder.h"
#include "cli/commands.h"
#include "io/scene_io.h"

namespace relight::cli {

namespace {

// The G-buffer must be the analysis's: same seed and sub-pixel samples.
AnalysisOptions gbuffer_options(AnalysisOptions options, const std::string& analysis_folder, const Analysis& analysis) {
  if (!analysis_folder.empty()) {
    options.seed = analysis.options.seed;
    options.gbuffer_samples = analysis.options.gbuffer_samples;
  }
  return options;
}

}  // namespace

AnalysedScene::AnalysedScene(const std::string& scene_path, const std::string& analysis_folder, AnalysisOptions options,
                             Progress& progress)
    : AnalysedScene(load_scene(scene_path, progress), scene_path, analysis_folder, options, progress) {}

AnalysedScene::AnalysedScene(Scene scene, const std::string& scene_path, const std::string& analysis_folder,
                             AnalysisOptions options, Progress& progress)
    : analysis(analysis_folder.empty() ? Analysis{} : load_analysis(analysis_folder, scene)),
      loaded(prepare_for_rendering(std::move(scene), scene_path, gbuffer_options(options, analysis_folder, analysis))) {
  if (analysis_folder.empty()) {
    options.strategy = default_strategy(loaded.scene);
    analysis = analyze(loaded.scene, *loaded.rays, *loaded.gbuffer, options, progress);
  }
}

}  // namespace relight::cli
