#include "analysis/strategy.h"

#include <algorithm>

#include "analysis/probe_cleanup.h"
#include "analysis/probe_lights.h"
#include "core/error.h"
#include "io/image_io.h"

namespace relight {

const char* to_string(Strategy s) {
  switch (s) {
    case Strategy::lights: return "lights";
    case Strategy::probe: return "probe";
    case Strategy::combined: return "combined";
  }
  return "?";
}

std::optional<Strategy> parse_strategy(const std::string& s) {
  if (s == "lights") return Strategy::lights;
  if (s == "probe") return Strategy::probe;
  if (s == "combined") return Strategy::combined;
  return std::nullopt;
}

Strategy default_strategy(const Scene& scene) {
  if (scene.probes.empty()) return Strategy::lights;
  return scene.lights.empty() ? Strategy::probe : Strategy::combined;
}

void check_strategy(const Scene& scene, Strategy strategy) {
  if (strategy != Strategy::lights && scene.probes.empty())
    throw InputError(scene.path.string(), "/probes",
                     std::string("strategy '") + to_string(strategy) + "' needs at least one light probe");
  const bool lights_emit = std::any_of(scene.lights.begin(), scene.lights.end(),
                                       [](const Light& l) { return l.enabled && !l.emission().isZero(); });
  const bool probes_emit =
      std::any_of(scene.probes.begin(), scene.probes.end(), [](const Probe& p) { return !is_black(p.image); });
  if (strategy == Strategy::probe && !probes_emit)
    throw InputError(scene.path.string(), "/probes",
                     "every probe image is black: strategy 'probe' lights the scene with the probes alone, and they "
                     "measured no light (check the probe's exposure, or use --strategy lights)");
  const bool environment_emits = strategy == Strategy::lights ? !scene.background.isZero() : probes_emit;
  if (strategy != Strategy::probe && !lights_emit && !environment_emits)
    throw InputError(scene.path.string(), "/lights",
                     "nothing lights the scene: every light is black (colour [0, 0, 0]) or disabled, and the " +
                         std::string(strategy == Strategy::lights ? "background is black" : "probes are black"));
}

Environment strategy_environment(const Scene& scene, const RayScene& rays, Strategy strategy) {
  if (strategy == Strategy::lights) return Environment::constant(scene.background);
  // What the probes cannot see takes the scene's background, where it gives one.
  const std::optional<Vec3> unseen =
      scene.background.isZero() ? std::nullopt : std::optional<Vec3>(scene.background);
  std::vector<Probe> cleaned;
  for (const auto& p : scene.probes)
    if (std::optional<Probe> distant = remove_local_geometry_from_probe(p, rays, unseen))
      cleaned.push_back(strategy == Strategy::combined ? remove_lights_from_probe(*distant, scene.lights)
                                                       : std::move(*distant));
  // Probes that all see only the geometry (a closed room) leave the
  // background, black or not: no path tracer's bounce then samples an
  // environment no ray can reach.
  if (cleaned.empty()) return Environment::constant(scene.background);
  return Environment::from_probes(cleaned);
}

Lighting strategy_lighting(const Scene& scene, const RayScene& rays, Strategy strategy) {
  Lighting lighting;
  if (strategy != Strategy::probe) lighting.lights = scene.lights;
  lighting.environment = strategy_environment(scene, rays, strategy);
  return lighting;
}

}  // namespace relight
