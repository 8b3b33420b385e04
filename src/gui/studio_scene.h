// StudioScene: a scene loaded for interactive relighting — its geometry,
// ray-tracing structure, G-buffer and analysis. The analysis is cached in a
// folder next to the scene (SCENE.analysis/), so reopening a scene whose
// inputs have not changed skips the analysis.
#pragma once

#include <filesystem>
#include <memory>

#include "analysis/analysed_scene.h"
#include "core/progress.h"
#include "render/ray_scene.h"

namespace relight::gui {

struct StudioScene {
  std::unique_ptr<const AnalysedScene> analysed;
  bool from_cache = false;  // the analysis was read from the cache folder
};

// The cache folder of a scene: "room/scene.json" -> "room/scene.analysis".
std::filesystem::path analysis_cache_folder(const std::filesystem::path& scene_path);

// Loads scene.json and its analysis: from the cache folder where it holds one
// for these inputs, else analysed now with `options` (the strategy the
// scene's data suggests) and written to the cache. A cache that cannot be
// written is only a warning. Throws InputError for a bad scene, Cancelled if
// progress is cancelled.
std::unique_ptr<StudioScene> load_studio_scene(const std::filesystem::path& scene_path, const AnalysisOptions& options,
                                               Progress& progress);

}  // namespace relight::gui
