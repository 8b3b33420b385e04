// The frames of an animated rig (scene/animation.h). Light transport is
// linear: a frame's illumination is the sum over its lights of colour x
// power x that light's illumination at unit emission, plus the
// environment's x environment_scale. Each light's unit image is rendered
// once for where it is and kept; a frame renders only the lights that moved
// (or turned, or changed shape) since the frames before, and recolouring,
// dimming or switching a light costs no ray.
//
// Every unit image is rendered with the analysis's seed, so it depends only
// on the light's geometry: a frame is the same image whichever frames were
// rendered before it, in this process or another (a render farm's chunks).
#pragma once

#include <memory>
#include <vector>

#include "relight/render_rig.h"

namespace relight {

class FrameSequence {
 public:
  // Holds a reference to `analysed`.
  FrameSequence(const AnalysedScene& analysed, const RenderOptions& options);

  // The re-lit photo under `rig` at `frame` (its keys applied).
  Image render(const Rig& rig, int frame, Progress& progress);

  // What the cache saved: unit images rendered and reused so far.
  struct Stats {
    int light_renders = 0, light_reuses = 0, environment_renders = 0;
  };
  const Stats& stats() const { return stats_; }

 private:
  struct LightLayer {
    Light light;  // unit emission
    IlluminationImages images;
    int last_used = 0;  // the call that last used it
  };
  // A layer for `light`'s geometry not yet used in this call, marked used; or null.
  LightLayer* kept_layer(const Light& light);
  const IlluminationImages& light_layer(const Light& light, Progress& progress);
  const IlluminationImages& environment_layer(const std::optional<RigEnvironment>& environment, Progress& progress);

  const AnalysedScene& analysed_;
  RenderOptions options_;
  NewIllumination illumination_;
  RelitLayers photo_layers_;
  std::vector<LightLayer> lights_;
  // The environment's layer and the rig environment it was rendered for.
  std::unique_ptr<IlluminationImages> environment_;
  std::optional<RigEnvironment> environment_for_;
  int calls_ = 0;
  Stats stats_;
};

}  // namespace relight
