// Warnings about a scene that loads but is likely mistaken, from what the
// camera sees (its G-buffer): geometry covering almost none of the photo,
// geometry at a depth a hundred times off the lights' and probes' distances
// (a unit mixed up), a light that lights nothing in view, a light whose
// rectangle or sphere passes through a wall (its size or place wrong). Given before
// `fit` and `analyze` start, so that a mistake is named before the work.
#pragma once

#include <string>

#include "core/image.h"
#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

void warn_about_the_view(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer);

// The share of the fully covered pixels of `albedo` (photo-sized) where it
// is above 1.
double share_above_one(const GBuffer& gbuffer, const Image& albedo);

// After the division: an albedo above 1 is no surface (it reflects more than
// it receives). Warns, naming the scene file, where that holds on more than
// 1 % of the fully covered pixels of `albedo` (photo-sized), or for the
// surfaces the camera does not see (`unseen`): the lights given are too weak
// for the photo (a light missing, its power too low, a probe forgotten).
// `lighting` says which lighting gave it ("the fitted lighting", ...).
void warn_about_albedo_above_one(const std::string& scene_file, const GBuffer& gbuffer, const Image& albedo,
                                 const Vec3& unseen, const char* lighting);

}  // namespace relight
