// Removing the principal lights from a light probe: a probe photographs the
// lamps and the sun too, so rendering with both the lights and the probe would
// light the scene twice (thesis 3.7). Each light's disc in the probe, with a
// margin, is replaced by the median radiance of the ring around it.
#pragma once

#include <vector>

#include "scene/light.h"
#include "scene/probe.h"

namespace relight {

Probe remove_lights_from_probe(const Probe& probe, const std::vector<Light>& lights);

}  // namespace relight
