// Making a light probe a faithful "distant environment". A probe photographs
// everything around its position, but the renderer needs only the light from
// what the geometry does not model:
// - the principal lights (lamps, the sun) are in the probe too, and rendering
//   with both would light the scene twice (thesis 3.7): each light's disc, with
//   a margin, is replaced by the median radiance of the ring around it;
// - the modelled geometry (walls, columns) is in the probe as seen from one
//   point, which is wrong everywhere else (thesis 3.6): the directions in which
//   a ray from the probe hits the geometry are filled from the neighbouring
//   distant environment.
#pragma once

#include <vector>

#include "render/ray_scene.h"
#include "scene/light.h"
#include "scene/probe.h"

namespace relight {

Probe remove_lights_from_probe(const Probe& probe, const std::vector<Light>& lights);

Probe remove_local_geometry_from_probe(const Probe& probe, const RayScene& rays);

}  // namespace relight
