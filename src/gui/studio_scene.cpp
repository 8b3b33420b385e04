#include "gui/studio_scene.h"

#include <spdlog/spdlog.h>

#include "analysis/analysis_folder.h"
#include "analysis/strategy.h"
#include "core/error.h"
#include "io/scene_io.h"

namespace relight::gui {

namespace fs = std::filesystem;

fs::path analysis_cache_folder(const fs::path& scene_path) {
  return fs::path(scene_path).replace_extension(".analysis");
}

std::unique_ptr<StudioScene> load_studio_scene(const fs::path& scene_path, const AnalysisOptions& options,
                                               Progress& progress) {
  auto s = std::make_unique<StudioScene>();
  s->scene = load_scene(scene_path, progress);
  s->rays = std::make_unique<RayScene>(s->scene.mesh);
  const fs::path cache = analysis_cache_folder(scene_path);
  try {
    s->analysis = load_analysis(cache, s->scene);
    s->from_cache = true;
  } catch (const InputError& stale_or_missing) {
    spdlog::info("analysing the scene ({})", stale_or_missing.what());
  }
  if (s->from_cache) {
    // The G-buffer must be the analysis's own: its seed and sub-pixel samples.
    s->gbuffer = std::make_unique<GBuffer>(scene_gbuffer(s->scene, *s->rays, s->analysis.options));
    return s;
  }
  AnalysisOptions analysis_options = options;
  analysis_options.strategy = default_strategy(s->scene);
  s->gbuffer = std::make_unique<GBuffer>(scene_gbuffer(s->scene, *s->rays, analysis_options));
  s->analysis = analyze(s->scene, *s->rays, *s->gbuffer, analysis_options, progress);
  try {
    save_analysis(cache, s->analysis, s->scene);
  } catch (const std::exception& e) {
    spdlog::warn("{}: the analysis cache cannot be written ({}); the next open analyses again", cache.string(),
                 e.what());
  }
  return s;
}

}  // namespace relight::gui
