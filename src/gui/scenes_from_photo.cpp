#include "gui/scenes_from_photo.h"

#include <algorithm>

#include "analysis/camera_registration.h"
#include "analysis/fit.h"
#include "io/atomic_file.h"
#include "io/scene_io.h"

namespace relight::gui {

namespace fs = std::filesystem;

std::vector<MaterialEstimate> write_scene_with_materials(const StudioScene& open, const fs::path& scene_file,
                                                         const fs::path& out, Progress& progress) {
  const AnalysedScene& a = *open.analysed;
  require_named_objects(a.scene());
  // A fresh analysis, as `relight materials` makes, of the photo reduced as
  // it reduces it: a cached one keeps no illumination to compare the photo with.
  Scene scene = a.scene();
  reduce_photo(scene, kEstimationPixels, "materials");
  const GBuffer gbuffer = scene_gbuffer(scene, a.rays(), a.analysis().options);
  const Analysis analysis = analyze(scene, a.rays(), gbuffer, a.analysis().options, progress);
  MaterialEstimationOptions estimation;
  estimation.paths_per_pixel = a.analysis().options.paths_per_pixel;
  estimation.seed = a.analysis().options.seed;
  std::vector<MaterialEstimate> estimates =
      estimate_materials(scene, a.rays(), gbuffer, analysis, estimation, progress);
  if (std::none_of(estimates.begin(), estimates.end(), [](const MaterialEstimate& m) { return bool(m.gloss); }))
    return estimates;
  Scene given = load_scene(scene_file, progress);  // its camera as given, not as an analysis registered it
  set_materials(given, with_estimates(given.materials, estimates));
  write_text_atomically(out, scene_to_json(given, out.parent_path()));
  return estimates;
}

SceneMatch write_scene_matched_to_photo(const fs::path& scene_file, const fs::path& out, const AnalysisOptions& options,
                                        Progress& progress) {
  SceneMatch match;
  Scene scene = load_scene(scene_file, progress);  // its camera as given, not as an analysis registered it
  const RayScene rays(scene.mesh);
  // As every analysis takes it: a camera already right is not nudged by the
  // edge fit's noise, and a match beyond the refusal range is reported, not
  // "fixed".
  const CameraCheck check = check_camera(scene, rays, progress);
  if (check.registered) {
    match.lines = describe_registration(*check.registered, scene.camera.width(), scene.camera.height());
    match.camera_moved_px = check.moved_px;
  } else {
    match.lines.push_back("camera kept as given: " + check.kept_because);
  }
  FitOptions fit;
  fit.seed = options.seed;
  fit.refine_placement = true;
  const FitResult fitted = fit_lighting(scene, rays, scene_gbuffer(scene, rays, options), fit, progress);
  for (std::string& line : describe_fit(fitted)) match.lines.push_back(std::move(line));
  match.lights_moved = int(std::count_if(fitted.placement.begin(), fitted.placement.end(), [](const PlacedLight& p) {
    return p.moved_m() > 0.0f || p.turned_deg() > 0.0f;
  }));
  write_text_atomically(out, scene_to_json(fitted.scene, out.parent_path()));
  return match;
}

}  // namespace relight::gui
