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
#include "relight/view.h"
#include "render/ray_scene.h"

namespace relight::gui {

struct StudioScene {
  std::unique_ptr<const AnalysedScene> analysed;
  bool from_cache = false;                // the analysis was read from a folder, not made now
  bool preview = false;                   // a quick analysis (preview_options), to be replaced by the full one
  std::filesystem::path analysis_folder;  // where it was read from or written to
  // The relighting session's view (RelightSession): the photo's size, or
  // smaller for a photo wider than StudioLoad::max_view_width. Made with the
  // analysis, off the window's thread (its own G-buffer and the analysis's
  // layers resampled: seconds at 8 Mpixel). Declared after `analysed`, which
  // it reads.
  std::shared_ptr<const RelightView> session_view;
  // The geometry's edges through the camera, drawn over the photo
  // (geometry_overlay.h): at the session view's size, as the photo is shown
  // (a photo-sized image of a 24-Mpixel photo was 96 MB, scaled down at
  // every paint); made with the view, off the window's thread.
  QImage geometry_edges;
  // The photo as the window shows it ("before" the re-lit image): at the
  // session view's size, and the exposure that shows it well
  // (display_exposure_for). Made off the window's thread, which took 0.5 s
  // at 8 Mpixel to encode and measure the full-size photo.
  const Image& shown_photo() const { return reduced_photo.empty() ? analysed->scene().photo : reduced_photo; }
  Image reduced_photo;  // empty where the view is the photo's size
  float display_exposure = 0.0f;
};

// How load_studio_scene reads or makes a scene's analysis and view.
struct StudioLoad {
  AnalysisOptions analysis;               // a scene without an analysis is analysed with these
  std::filesystem::path analysis_folder;  // an analysis `relight analyze` made; empty: the cache folder's
  int64_t preview_above_pixels = 0;       // a larger photo gets a preview analysis first (0: never)
  int max_view_width = 0;                 // a wider photo is shown and edited this wide (0: at its own size)
};

// The cache folder of a scene: "room/scene.json" -> "room/scene.analysis".
std::filesystem::path analysis_cache_folder(const std::filesystem::path& scene_path);

// Loads scene.json and its analysis: from `load.analysis_folder` where one
// is given (a missing, stale or mixed one is an InputError, never analysed
// over); else from the cache folder where it holds one for these inputs,
// else analysed now with `load.analysis` (the strategy the scene's data
// suggests) and written to the cache. A cache that cannot be written is only
// a warning. Throws InputError for a bad scene, Cancelled if progress is
// cancelled. Where it would analyse a photo of over
// `load.preview_above_pixels` it makes a preview analysis instead (not
// cached; StudioScene::preview), for a full one to follow. The geometry's
// edges and the session's view are made with it.
std::unique_ptr<StudioScene> load_studio_scene(const std::filesystem::path& scene_path, const StudioLoad& load,
                                               Progress& progress);

}  // namespace relight::gui
