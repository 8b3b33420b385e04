#include "relight/frame_sequence.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>

#include "render/direct_light.h"
#include "scene/animation.h"

namespace relight {

namespace {

bool same_environment(const std::optional<RigEnvironment>& a, const std::optional<RigEnvironment>& b) {
  if (a.has_value() != b.has_value()) return false;
  return !a || (a->image == b->image && a->color == b->color);
}

// out += weight x layer, pixel by pixel.
void accumulate(Image& out, const Image& layer, const Vec3& weight) {
  tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) out.pixels[i] += weight.cwiseProduct(layer.pixels[i]);
  });
}

}  // namespace

FrameSequence::FrameSequence(const AnalysedScene& analysed, const RenderOptions& options)
    : analysed_(analysed),
      options_(options),
      illumination_(analysed),
      photo_layers_(photo_layers(analysed.scene(), analysed.analysis())) {}

FrameSequence::LightLayer* FrameSequence::kept_layer(const Light& light) {
  for (LightLayer& layer : lights_)
    if (layer.last_used != calls_ && same_geometry(layer.light, light)) {
      layer.last_used = calls_;
      return &layer;
    }
  return nullptr;
}

const IlluminationImages& FrameSequence::light_layer(const Light& light, Progress& progress) {
  if (LightLayer* kept = kept_layer(light)) {
    ++stats_.light_reuses;
    return kept->images;
  }
  Lighting lighting;
  lighting.lights = {unit_light(light)};
  lighting.lights.front().keys.clear();
  IlluminationImages images = illumination_.render(analysed_.gbuffer(), analysed_.scene().camera, lighting, options_,
                                                   progress, "light " + light.name);
  ++stats_.light_renders;
  lights_.push_back({lighting.lights.front(), std::move(images), calls_});
  return lights_.back().images;
}

const IlluminationImages& FrameSequence::environment_layer(const std::optional<RigEnvironment>& environment,
                                                           Progress& progress) {
  if (!environment_ || !same_environment(environment_for_, environment)) {
    Lighting lighting;
    lighting.environment = illumination_.environment(environment);
    environment_ = std::make_unique<IlluminationImages>(illumination_.render(
        analysed_.gbuffer(), analysed_.scene().camera, lighting, options_, progress, "environment"));
    environment_for_ = environment;
    ++stats_.environment_renders;
  }
  return *environment_;
}

Image FrameSequence::render(const Rig& animated, int frame, Progress& progress) {
  ++calls_;
  const Rig rig = rig_at_frame(animated, frame);
  const Camera& camera = analysed_.scene().camera;
  IlluminationImages light{Image(camera.width(), camera.height()), Image(camera.width(), camera.height())};
  if (rig.environment_scale > 0.0f) {
    const IlluminationImages& environment = environment_layer(rig.environment, progress);
    accumulate(light.surface, environment.surface, Vec3::Constant(rig.environment_scale));
    accumulate(light.background, environment.background, Vec3::Constant(rig.environment_scale));
  }
  // A layer serves one light a frame: two lights in one place (a pair of
  // bulbs) take one each. A light switched off keeps its layer for when it
  // comes back on.
  for (const Light& l : rig.lights)
    if (l.enabled && !l.emission().isZero()) accumulate(light.surface, light_layer(l, progress).surface, l.emission());
  for (const Light& l : rig.lights)
    if (!l.enabled || l.emission().isZero()) kept_layer(l);
  // The other layers are of places the lights have left.
  std::erase_if(lights_, [&](const LightLayer& layer) { return layer.last_used != calls_; });
  return relit_image(photo_layers_, analysed_.analysis().coverage, light, rig);
}

}  // namespace relight
