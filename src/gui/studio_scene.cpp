#include "gui/studio_scene.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>

#include "analysis/analysis_folder.h"
#include "analysis/strategy.h"
#include "core/error.h"
#include "gui/geometry_overlay.h"
#include "gui/tone_map.h"
#include "io/image_io.h"
#include "io/scene_io.h"

namespace relight::gui {

namespace fs = std::filesystem;

fs::path analysis_cache_folder(const fs::path& scene_path) {
  return fs::path(scene_path).replace_extension(".analysis");
}

namespace {

// The scene and its analysis, read or made.
std::unique_ptr<StudioScene> analysed_studio_scene(const fs::path& scene_path, const AnalysisOptions& options,
                                                   Progress& progress, const fs::path& analysis_folder,
                                                   int64_t preview_above_pixels) {
  auto s = std::make_unique<StudioScene>();
  Scene scene = load_scene(scene_path, progress);
  if (!analysis_folder.empty()) {
    s->analysed = AnalysedScene::from_folder(std::move(scene), analysis_folder);
    s->from_cache = true;
    s->analysis_folder = analysis_folder;
    return s;
  }
  const fs::path cache = analysis_cache_folder(scene_path);
  s->analysis_folder = cache;
  try {
    s->analysed = AnalysedScene::from_folder(std::move(scene), cache);
    s->from_cache = true;
    return s;
  } catch (const InputError& stale_or_missing) {
    spdlog::info("analysing the scene ({})", stale_or_missing.what());
  }
  AnalysisOptions analysis_options = options;
  analysis_options.strategy = default_strategy(scene);
  if (preview_above_pixels > 0 && int64_t(scene.photo.width) * scene.photo.height > preview_above_pixels) {
    s->analysed = AnalysedScene::analyse(std::move(scene), preview_options(analysis_options), progress);
    s->preview = true;
    return s;
  }
  std::unique_ptr<AnalysedScene> analysed = AnalysedScene::analyse(std::move(scene), analysis_options, progress);
  try {
    save_analysis(cache, analysed->analysis(), analysed->scene());
  } catch (const std::exception& e) {
    spdlog::warn("{}: the analysis cache cannot be written ({}); the next open analyses again", cache.string(),
                 e.what());
  }
  s->analysed = std::move(analysed);
  return s;
}

}  // namespace

std::unique_ptr<StudioScene> load_studio_scene(const fs::path& scene_path, const StudioLoad& load, Progress& progress) {
  std::unique_ptr<StudioScene> s =
      analysed_studio_scene(scene_path, load.analysis, progress, load.analysis_folder, load.preview_above_pixels);
  // A photo wider than max_view_width is shown (and edited) that wide; 0, 0: at its own size.
  const Image& photo = s->analysed->scene().photo;
  int width = 0, height = 0;
  if (load.max_view_width > 0 && photo.width > load.max_view_width) {
    width = load.max_view_width;
    height = std::max(1, int(std::lround(double(photo.height) * width / photo.width)));
  }
  s->session_view = std::make_shared<const RelightView>(*s->analysed, width, height);
  s->geometry_edges = geometry_edges_image(s->session_view->gbuffer());
  if (width > 0) s->reduced_photo = resized(photo, width, height);
  s->display_exposure = display_exposure_for(s->shown_photo());
  return s;
}

}  // namespace relight::gui
