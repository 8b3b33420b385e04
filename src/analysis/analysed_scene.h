// AnalysedScene: a scene with its analysis, what every front end relights
// from (relight render and preview, the interactive session, the studio, the
// tests and benches). It owns the scene, its ray-tracing structure, the
// analysis's own G-buffer (made with the analysis's seed and sub-pixel
// samples: a later render's noise then follows the analysis's, and an
// unchanged rig gives the photo back), the analysis, and the environment as
// the analysis's strategy cleaned it. Built only by the loaders below, so the
// G-buffer is always the analysis's (through its camera, which is the
// scene's unless the analysis registered it to the photo); never moved (the rays refer to the
// scene's mesh).
#pragma once

#include <filesystem>
#include <memory>

#include "analysis/analyze.h"
#include "analysis/surface_albedo.h"

namespace relight {

class AnalysedScene {
 public:
  // The analysis read from a folder `relight analyze` wrote for this scene
  // (InputError where it is missing, stale or mixed: analysis_folder.h;
  // `scene` is then left as it was).
  static std::unique_ptr<AnalysedScene> from_folder(Scene&& scene, const std::filesystem::path& folder);
  // The scene analysed now with `options` (their seed and sub-pixel samples
  // make the G-buffer).
  static std::unique_ptr<AnalysedScene> analyse(Scene&& scene, const AnalysisOptions& options, Progress& progress,
                                                const AlbedoObserver& on_albedo = {});

  AnalysedScene(const AnalysedScene&) = delete;
  AnalysedScene& operator=(const AnalysedScene&) = delete;

  const Scene& scene() const { return scene_; }
  const RayScene& rays() const { return *rays_; }
  const GBuffer& gbuffer() const { return *gbuffer_; }
  const Analysis& analysis() const { return analysis_; }
  // The photo's environment at scale 1: the probes or the background, as
  // the analysis's strategy takes them (the modelled lights cleaned out).
  const Environment& environment() const { return environment_; }
  // The recovered albedo as light bouncing off a surface point takes it: the
  // pixel showing the point, else its triangle's mean. Made once here (its
  // triangle means are a pass over the photo: 0.13 s at 8 Mpixel), not by
  // every render or session of the scene.
  const PhotoAlbedo& bounce_albedo() const { return *bounce_albedo_; }

 private:
  explicit AnalysedScene(Scene scene);  // the G-buffer follows, through the analysis's camera
  void set_analysis(Analysis analysis);

  Scene scene_;
  std::unique_ptr<RayScene> rays_;
  std::unique_ptr<GBuffer> gbuffer_;
  Analysis analysis_;
  Environment environment_;
  std::unique_ptr<PhotoAlbedo> bounce_albedo_;
};

}  // namespace relight
