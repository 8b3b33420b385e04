// StudioScene: a scene loaded for interactive relighting — its geometry,
// ray-tracing structure, G-buffer and analysis. The analysis is cached in a
// folder next to the scene (SCENE.analysis/), so reopening a scene whose
// inputs have not changed skips the analysis.
#pragma once

#include <QImage>
#include <filesystem>
#include <memory>

#include "analysis/analysed_scene.h"
#include "core/progress.h"
#include "render/ray_scene.h"

namespace relight::gui {

struct StudioScene {
  std::unique_ptr<const AnalysedScene> analysed;
  bool from_cache = false;                // the analysis was read from a folder, not made now
  bool preview = false;                   // a quick analysis (preview_options), to be replaced by the full one
  std::filesystem::path analysis_folder;  // where it was read from or written to
  // The geometry's edges through the camera, drawn over the photo
  // (geometry_overlay.h): made with the analysis, off the window's thread
  // (0.36 s at 8 Mpixel).
  QImage geometry_edges;
};

// The cache folder of a scene: "room/scene.json" -> "room/scene.analysis".
std::filesystem::path analysis_cache_folder(const std::filesystem::path& scene_path);

// Loads scene.json and its analysis: from `analysis_folder` where one is
// given (an analysis `relight analyze` made; a missing, stale or mixed one is
// an InputError, never analysed over); else from the cache folder where it
// holds one for these inputs, else analysed now with `options` (the strategy
// the scene's data suggests) and written to the cache. A cache that cannot be
// written is only a warning. Throws InputError for a bad scene, Cancelled if
// progress is cancelled. Where it would analyse a photo of over
// `preview_above_pixels` (0: never) it makes a preview analysis instead
// (not cached; StudioScene::preview), for a full one to follow. The
// geometry's edges are drawn with it.
std::unique_ptr<StudioScene> load_studio_scene(const std::filesystem::path& scene_path, const AnalysisOptions& options,
                                               Progress& progress, const std::filesystem::path& analysis_folder = {},
                                               int64_t preview_above_pixels = 0);

}  // namespace relight::gui
