// Making a light probe a faithful "distant environment". A probe photographs
// everything around its position, but the renderer needs only the light from
// what the geometry does not model. The modelled geometry (walls, columns) is
// in the probe as seen from one point, which is wrong everywhere else (thesis
// 3.6): the directions in which a ray from the probe hits the geometry are
// filled from the neighbouring distant environment. (The principal lights are
// taken out by probe_lights.h.)
#pragma once

#include <vector>

#include "render/ray_scene.h"
#include "scene/probe.h"

namespace relight {

Probe remove_local_geometry_from_probe(const Probe& probe, const RayScene& rays);

// The probe's mean radiance over all directions (solid-angle weighted): what
// a constant `background` standing for it should be.
Vec3 mean_radiance(const Probe& probe);

}  // namespace relight
