// Relighting: the photo under a new lighting design. The new illumination
// (direct light of the rig, the scene's environment x environment_scale, and
// interreflection off the recovered albedo) multiplies the albedo (thesis
// chapter 5's modulation, done offline by path tracing).
#pragma once

#include "analysis/analyze.h"

namespace relight {

struct RenderOptions {
  int paths_per_pixel = 64;
  int max_bounces = 4;
};

// The re-lit photo. Pixels that see no geometry show the photo's background
// times the rig's environment_scale.
Image render_rig(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const Analysis& analysis,
                 const Rig& rig, const RenderOptions& options, Progress& progress);

// A rig holding the scene's own lights and its environment unchanged.
Rig rig_from_scene(const Scene& scene);

}  // namespace relight
