// The thesis's three strategies for simulating the light the photo was taken
// under (section 3.5): the principal lights with a constant background, the
// light probes alone, or both — with the principal lights removed from the
// probes so that nothing is lit twice.
#pragma once

#include <optional>
#include <string>

#include "render/integrator.h"
#include "scene/scene.h"

namespace relight {

enum class Strategy { lights, probe, combined };

const char* to_string(Strategy s);
std::optional<Strategy> parse_strategy(const std::string& s);
// combined where the scene has both lights and probes, else whichever it has.
Strategy default_strategy(const Scene& scene);
// Throws InputError when the scene lacks what the strategy needs, or when
// what it lights the scene with gives no light at all (every light black or
// disabled and the background black; for 'probe', every probe image black):
// the photo would be divided by zero, or by the little light that is left.
void check_strategy(const Scene& scene, Strategy strategy);

// The scene's environment as the strategy models it: the background, or the
// probes with the modelled geometry taken out of them, and for `combined` the
// principal lights too (probe_cleanup.h).
Environment strategy_environment(const Scene& scene, const RayScene& rays, Strategy strategy);
// The full original lighting under a strategy.
Lighting strategy_lighting(const Scene& scene, const RayScene& rays, Strategy strategy);

}  // namespace relight
