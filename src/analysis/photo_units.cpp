#include "analysis/photo_units.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <vector>

namespace relight {

PhotoUnits photo_units_against_the_probes(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer,
                                          bool keep_vignetting) {
  std::vector<std::vector<SharedPoint>> shared;
  for (const Probe& probe : scene.probes) shared.push_back(points_shared_with_photo(probe, scene, rays, gbuffer));
  // Per probe: the photo's exposure against it, where it shows the scene as `photo` does.
  const auto exposures_of = [&](const Image& photo) {
    std::vector<std::optional<ProbeExposure>> e;
    for (size_t p = 0; p < shared.size(); ++p) e.push_back(photo_exposure_from(shared[p], photo, scene.probes[p].path));
    return e;
  };
  const auto any = [](const std::vector<std::optional<ProbeExposure>>& e) {
    return std::any_of(e.begin(), e.end(), [](const auto& x) { return x.has_value(); });
  };
  std::vector<std::optional<ProbeExposure>> exposures = exposures_of(scene.photo);
  PhotoUnits units;
  if (!keep_vignetting) {
    // The probe that shares the most points decides, as for the exposure
    // (pooled, the bookcase's mirror ball, 10 % brighter at the photo's
    // corners than its equirect beside it, drew the fit 0.678 for 0.65).
    // A strong vignetting can make photo / probe vary as much as the photo
    // does: where no probe shows the scene as the photo does, every probe
    // that shares enough is a candidate, and the falloff is kept where the
    // photo without it matches one.
    const bool matched = any(exposures);
    std::optional<size_t> decider;
    for (size_t p = 0; p < shared.size(); ++p)
      if ((matched ? exposures[p].has_value() : shared[p].size() >= kMinExposurePoints) &&
          (!decider || shared[p].size() > shared[*decider].size()))
        decider = p;
    std::optional<VignettingFit> fit;
    if (decider) fit = fit_vignetting(shared[*decider], scene.photo);
    if (fit && is_lens_vignetting(*fit)) {
      Image devignetted = scene.photo;
      remove_vignetting(devignetted, fit->falloff);
      std::vector<std::optional<ProbeExposure>> without = exposures_of(devignetted);
      if (matched || any(without))
        exposures = std::move(without);
      else
        fit.reset();
    }
    if (fit) units.vignetting = photo_vignetting(*fit, scene.path.string());
  }
  units.probe_exposures = exposures;
  std::optional<ProbeExposure> best;
  const Probe* best_probe = nullptr;
  for (size_t p = 0; p < exposures.size(); ++p)
    if (exposures[p] && (!best || exposures[p]->points > best->points))
      best = exposures[p], best_probe = &scene.probes[p];
  if (!best) {
    if (!scene.probes.empty())
      spdlog::info(
          "exposure: no probe shows enough of the photo's surfaces as the photo does to match their "
          "exposures; the photo is taken to be in the probes' units");
    return units;
  }
  const Vec3& k = best->photo_over_probe;
  spdlog::info(
      "exposure: the photo shows the surfaces {:.3f} {:.3f} {:.3f} times as bright as {} does ({} points, "
      "spread {:.3f}, photo spread {:.3f})",
      k.x(), k.y(), k.z(), best_probe->path, best->points, best->spread, best->photo_spread);
  if (!exposure_differs(k)) return units;
  units.exposure = k;
  units.exposure_probe = best_probe->path;
  return units;
}

}  // namespace relight
