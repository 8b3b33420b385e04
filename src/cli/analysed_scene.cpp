// The scene and analysis that render and preview work from.
#include "analysis/strategy.h"
#include "cli/commands.h"
#include "io/scene_io.h"

namespace relight::cli {

std::unique_ptr<AnalysedScene> load_analysed_scene(const std::string& scene_path, const std::string& analysis_folder,
                                                   AnalysisOptions options, Progress& progress) {
  Scene scene = load_scene(scene_path, progress);
  log_scene(scene, scene_path);
  return analysed_scene(std::move(scene), analysis_folder, options, progress);
}

std::unique_ptr<AnalysedScene> analysed_scene(Scene&& scene, const std::string& analysis_folder,
                                              AnalysisOptions options, Progress& progress) {
  if (!analysis_folder.empty()) return AnalysedScene::from_folder(std::move(scene), analysis_folder);
  options.strategy = default_strategy(scene);
  return AnalysedScene::analyse(std::move(scene), options, progress);
}

}  // namespace relight::cli
