// Warnings about a scene that loads but is likely mistaken, from what the
// camera sees (its G-buffer): geometry covering almost none of the photo,
// geometry at a depth a hundred times off the lights' and probes' distances
// (a unit mixed up), a light that lights nothing in view. Given before
// `fit` and `analyze` start, so that a mistake is named before the work.
#pragma once

#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

void warn_about_the_view(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer);

}  // namespace relight
