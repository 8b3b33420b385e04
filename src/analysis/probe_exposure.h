// The photo's exposure against a probe's. A photo and a probe (a chrome ball
// shot and merged on its own, its reflectance below 1) are rarely in the
// same units, and lights measured from the probe are in the probe's: the
// albedo would come out off by their ratio. Both show the scene's matte
// surfaces, whose radiance does not depend on where they are seen from, so
// the ratio is what the photo shows of a surface point over what the probe
// shows of the same point: per channel, the median over every point both see
// cleanly (away from silhouettes and creases in the probe, on the surface the
// camera sees in the photo, not clipped there).
#pragma once

#include <optional>

#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

struct ProbeExposure {
  Vec3 photo_over_probe = Vec3::Ones();  // multiply the probe by this to get the photo's units
  size_t points = 0;                     // surface points both see
  float spread = 0.0f;                   // of log luminance ratio (1.4826 x MAD) over them
};

// Fewer shared points than this fix no exposure.
constexpr size_t kMinExposurePoints = 100;

// Nothing where the probe and the photo share fewer than kMinExposurePoints
// surface points.
std::optional<ProbeExposure> photo_exposure_against_probe(const Probe& probe, const Scene& scene,
                                                          const RayScene& rays, const GBuffer& gbuffer);

}  // namespace relight
