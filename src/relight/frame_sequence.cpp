#include "relight/frame_sequence.h"

#include <spdlog/spdlog.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "render/direct_light.h"
#include "scene/animation.h"

namespace relight {

namespace {

// out += weight x layer, pixel by pixel.
void accumulate(Image& out, const Image& layer, const Vec3& weight) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) out.pixels[i] += weight.cwiseProduct(layer.pixels[i]);
  });
}

bool lit(const Light& light) { return light.enabled && !light.emission().isZero(); }

}  // namespace

FrameSequence::FrameSequence(const AnalysedScene& analysed, const Rig& rig, const RenderOptions& options)
    : analysed_(analysed),
      rig_(rig),
      options_(options),
      moving_options_(options),
      illumination_(analysed),
      photo_layers_(photo_layers(analysed.scene(), analysed.analysis())) {
  const Camera& camera = analysed.scene().camera;
  moving_options_.indirect_stride =
      2 * indirect_stride(illumination_.illumination_options(options), camera.width(), camera.height());
  for (const Light& light : rig.lights) moving_.push_back(moves(light));
}

FrameSequence::LightLayer* FrameSequence::kept_layer(const Light& light, bool moving) {
  for (LightLayer& layer : lights_)
    if (layer.last_used != calls_ && same_geometry(layer.light, light) && layer.moving == moving) {
      layer.last_used = calls_;
      return &layer;
    }
  return nullptr;
}

const IlluminationImages& FrameSequence::light_layer(const Light& light, bool moving, Progress& progress) {
  if (LightLayer* kept = kept_layer(light, moving)) {
    ++stats_.light_reuses;
    return kept->images;
  }
  Lighting lighting;
  lighting.lights = {unit_light(light)};
  // Kept paths keep no glossy surface's highlight of the lights along them.
  if (moving && !kept_paths_tried_ && analysed_.scene().gloss.all_matte()) {
    kept_paths_tried_ = true;
    kept_paths_ = std::make_unique<KeptPaths>(illumination_.keep_paths(analysed_.gbuffer(), moving_options_, progress));
    if (kept_paths_->within_budget()) {
      spdlog::info("the moving lights' bounce light follows paths kept for the sequence: {:.0f} MB",
                   double(kept_paths_->bytes()) / (1 << 20));
    } else {
      kept_paths_.reset();
      spdlog::info(
          "the paths of the moving lights' bounce light would take over {:.0f} MB to keep: each frame "
          "traces its own",
          double(KeptPaths::kDefaultBudget) / (1 << 20));
    }
  }
  IlluminationImages images =
      illumination_.render(analysed_.gbuffer(), analysed_.scene().camera, lighting, moving ? moving_options_ : options_,
                           progress, "light " + light.name, true, moving ? kept_paths_.get() : nullptr);
  ++stats_.light_renders;
  lights_.push_back({lighting.lights.front(), moving, std::move(images), calls_});
  return lights_.back().images;
}

const IlluminationImages& FrameSequence::still_layer(Progress& progress) {
  if (!still_) {
    Rig still = rig_;
    std::erase_if(still.lights, [](const Light& l) { return !l.keys.empty(); });
    still_ = std::make_unique<IlluminationImages>(
        illumination_.render(analysed_.gbuffer(), analysed_.scene().camera, illumination_.rig_lighting(still), options_,
                             progress, "the lights without keys and the environment"));
    ++stats_.still_renders;
  }
  return *still_;
}

Image FrameSequence::render(int frame, Progress& progress) {
  ++calls_;
  const Rig rig = rig_at_frame(rig_, frame);
  IlluminationImages light = still_layer(progress);
  // A layer serves one light a frame: two lights in one place (a pair of
  // bulbs) take one each. A light switched off keeps its layer for when it
  // comes back on.
  const auto keyed = [&](size_t i) { return !rig_.lights[i].keys.empty(); };
  for (size_t i = 0; i < rig.lights.size(); ++i)
    if (const Light& l = rig.lights[i]; keyed(i) && lit(l))
      accumulate(light.surface, light_layer(l, moving_[i], progress).surface, l.emission());
  for (size_t i = 0; i < rig.lights.size(); ++i)
    if (keyed(i) && !lit(rig.lights[i])) kept_layer(rig.lights[i], moving_[i]);
  // The other layers are of places the lights have left.
  std::erase_if(lights_, [&](const LightLayer& layer) { return layer.last_used != calls_; });
  Image relit = relit_image(photo_layers_, analysed_.analysis().coverage, light, rig);
  add_highlights(relit, analysed_.analysis().coverage,
                 illumination_.highlights(analysed_.gbuffer(), analysed_.scene().camera,
                                          illumination_.rig_lighting(rig), options_, progress));
  return relit;
}

}  // namespace relight
