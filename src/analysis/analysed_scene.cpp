#include "analysis/analysed_scene.h"

#include "analysis/analysis_folder.h"
#include "analysis/probe_exposure.h"
#include "analysis/strategy.h"

namespace relight {

AnalysedScene::AnalysedScene(Scene scene) : scene_(std::move(scene)), rays_(std::make_unique<RayScene>(scene_.mesh)) {}

void AnalysedScene::set_analysis(Analysis analysis) {
  analysis_ = std::move(analysis);
  // The analysis's units: the photo shows through where no geometry covers it.
  bring_to_analysis_units(scene_.photo, analysis_);
  environment_ = strategy_environment(scene_, *rays_, analysis_.options.strategy);
  const AlbedoImages& albedo = analysis_.albedo;
  bounce_albedo_ =
      std::make_unique<PhotoAlbedo>(scene_.camera, *gbuffer_, albedo.albedo, albedo.mean, albedo.unseen_triangles);
}

std::unique_ptr<AnalysedScene> AnalysedScene::from_folder(Scene&& scene, const std::filesystem::path& folder) {
  if (is_preview_analysis(folder)) reduce_for_preview(scene);
  Analysis analysis = load_analysis(folder, scene);
  if (analysis.registered_camera)
    scene.camera = Camera(*analysis.registered_camera, scene.camera.width(), scene.camera.height());
  std::unique_ptr<AnalysedScene> s(new AnalysedScene(std::move(scene)));
  s->gbuffer_ = std::make_unique<GBuffer>(scene_gbuffer(s->scene_, *s->rays_, analysis.options));
  s->set_analysis(std::move(analysis));
  return s;
}

std::unique_ptr<AnalysedScene> AnalysedScene::analyse(Scene&& scene, const AnalysisOptions& options, Progress& progress,
                                                      const AlbedoObserver& on_albedo) {
  if (options.preview) reduce_for_preview(scene);
  std::unique_ptr<AnalysedScene> s(new AnalysedScene(std::move(scene)));
  const std::optional<CameraSpec> registered = camera_for_analysis(s->scene_, *s->rays_, options, progress);
  s->gbuffer_ = std::make_unique<GBuffer>(scene_gbuffer(s->scene_, *s->rays_, options));
  Analysis analysis = analyze(s->scene_, *s->rays_, *s->gbuffer_, options, progress, on_albedo);
  analysis.registered_camera = registered;
  s->set_analysis(std::move(analysis));
  return s;
}

}  // namespace relight
