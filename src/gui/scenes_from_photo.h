// The scenes relight studio's File menu makes from the open one and its
// photo, each written to a file of its own (never over the open scene, which
// MainWindow checks): the work of `relight materials` and of `relight fit
// --register --refine-placement`, run on a worker thread (no Qt here).
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "analysis/material_estimation.h"
#include "gui/studio_scene.h"

namespace relight::gui {

// Estimates from the open scene's photo which of its objects shine (a fresh
// analysis, as `relight materials` makes) and, where any does, writes the
// scene file with them added to its `materials` to `out`.
std::vector<MaterialEstimate> write_scene_with_materials(const StudioScene& open,
                                                         const std::filesystem::path& scene_file,
                                                         const std::filesystem::path& out, Progress& progress);

struct SceneMatch {
  std::vector<std::string> lines;        // what `relight fit --register --refine-placement` prints
  std::optional<float> camera_moved_px;  // how far the registered camera moved the photo; none: kept
  int lights_moved = 0;                  // moved or turned to where their shadows fall
};

// The scene file matched to its photo, written to `out`: the camera
// registered to the photo's edges where the registered one is visibly better
// (as every analysis takes it; a match beyond the refusal range, or too few
// edges, keeps it and says why), then the lights' power and colour and the
// background fitted and the lights placed where their shadows fall.
SceneMatch write_scene_matched_to_photo(const std::filesystem::path& scene_file, const std::filesystem::path& out,
                                        const AnalysisOptions& options, Progress& progress);

}  // namespace relight::gui
