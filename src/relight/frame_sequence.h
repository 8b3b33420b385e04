// The frames of an animated rig (scene/animation.h). Light transport is
// linear: a frame's illumination is the still part's — the environment x
// environment_scale and the lights without keys, rendered together once —
// plus, for each keyed light, colour x power x its illumination at unit
// emission. A keyed light's unit image is rendered once for where it is and
// kept; a frame renders only the lights that moved (or turned) since the
// frame before, and recolouring, dimming or switching a light costs no ray.
// A rig without keys is one render, the still render's own.
//
// A light the keys move or turn is rendered again in most frames: its
// bounce light is traced at twice the still render's stride each way (a
// quarter of the pixels; the bounce light of one light is smooth), along
// paths from the camera traced once for the sequence and kept (KeptPaths:
// only their shadow rays to the light are traced again), its direct light
// at every pixel as always. Every unit image is rendered with
// the analysis's seed, so it depends only on the light's geometry and
// whether it moves: a frame is the same image whichever frames were
// rendered before it, in this process or another (a render farm's chunks).
#pragma once

#include <memory>
#include <vector>

#include "relight/render_rig.h"

namespace relight {

class FrameSequence {
 public:
  // Holds references to `analysed` and `rig`.
  FrameSequence(const AnalysedScene& analysed, const Rig& rig, const RenderOptions& options);

  // The re-lit photo under the rig at `frame` (its keys applied).
  Image render(int frame, Progress& progress);

  // What the cache saved: renders of the still part (the environment and
  // the lights without keys), of keyed lights, and keyed lights reused.
  struct Stats {
    int still_renders = 0, light_renders = 0, light_reuses = 0;
  };
  const Stats& stats() const { return stats_; }

 private:
  struct LightLayer {
    Light light;  // unit emission
    bool moving;
    IlluminationImages images;
    int last_used = 0;  // the call that last used it
  };
  // A layer for `light`'s geometry not yet used in this call, marked used; or null.
  LightLayer* kept_layer(const Light& light, bool moving);
  // `moving`: the light's keys move it (a layer of the sparser bounce light).
  const IlluminationImages& light_layer(const Light& light, bool moving, Progress& progress);
  const IlluminationImages& still_layer(Progress& progress);

  const AnalysedScene& analysed_;
  const Rig& rig_;
  RenderOptions options_, moving_options_;
  NewIllumination illumination_;
  RelitLayers photo_layers_;
  std::vector<bool> moving_;  // per light of the rig: its keys move or turn it
  std::vector<LightLayer> lights_;
  std::unique_ptr<IlluminationImages> still_;
  // The moving lights' bounce light's paths, kept once one is rendered
  // where they fit KeptPaths' budget.
  std::unique_ptr<KeptPaths> kept_paths_;
  bool kept_paths_tried_ = false;
  int calls_ = 0;
  Stats stats_;
};

}  // namespace relight
