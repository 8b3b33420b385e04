// The photo brought to the units of the probes. A probe in the scene sees
// its matte surfaces with no lens in between: photo / probe over the points
// both show is the photo's vignetting across its frame times its exposure
// against the probe. `relight analyze` divides both out before the division;
// `relight fit` the vignetting only (it brings the probes to the photo's
// exposure instead).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "analysis/probe_exposure.h"
#include "analysis/vignetting.h"
#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

// What brings the photo to the probes' units, from the points it shares
// with each probe that shows the scene as it does: its vignetting
// (vignetting.h), unless kept, then its exposure (probe_exposure.h), from
// the probe that shares the most points with it, where it differs from 1 by
// more than kExposureTolerance. Nothing of either where no probe shares
// enough. The probes' units are the lights' wherever the lights were
// measured from them (`relight fit`) or rendered with them (a Blender scene).
struct PhotoUnits {
  std::optional<Vignetting> vignetting;
  std::optional<Vec3> exposure;  // photo / probe, where it differs from 1
  std::string exposure_probe;    // the probe's file it was measured against
  // The photo's exposure against each probe (scene.probes' order), once its
  // vignetting is divided out where it is: nothing where a probe does not
  // show the scene as the photo does.
  std::vector<std::optional<ProbeExposure>> probe_exposures;
};
PhotoUnits photo_units_against_the_probes(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer,
                                          bool keep_vignetting);

}  // namespace relight
