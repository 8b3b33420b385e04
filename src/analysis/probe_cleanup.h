// Making a light probe a faithful "distant environment". A probe photographs
// everything around its position, but the renderer needs only the light from
// what the geometry does not model. The modelled geometry (walls, columns) is
// in the probe as seen from one point, which is wrong everywhere else (thesis
// 3.6): the directions in which any part of a probe pixel shows the geometry
// are replaced. (The principal lights are taken out by probe_lights.h.)
#pragma once

#include <optional>
#include <vector>

#include "render/ray_scene.h"
#include "scene/probe.h"

namespace relight {

// The probe shows nothing of the environment in those directions, yet points
// of the scene away from the probe look out through some of them (past the
// end of a floor that hides the lower half from the probe). `fill`, where
// given, is the radiance they take (the scene's `background`: the user's
// estimate of the environment); without, they are filled from the
// neighbouring environment, ring by ring, which carries the horizon's
// radiance into the whole lower half. A probe that shows the geometry in
// every direction (inside a closed room) shows nothing distant: nullopt.
std::optional<Probe> remove_local_geometry_from_probe(const Probe& probe, const RayScene& rays,
                                                      const std::optional<Vec3>& fill = std::nullopt);

// The probe's mean radiance over all directions (solid-angle weighted): what
// a constant `background` standing for it should be.
Vec3 mean_radiance(const Probe& probe);

}  // namespace relight
