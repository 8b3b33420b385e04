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

#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

struct ProbeExposure {
  Vec3 photo_over_probe = Vec3::Ones();  // multiply the probe by this to get the photo's units
  size_t points = 0;                     // surface points both see
  float spread = 0.0f;                   // of log luminance ratio (1.4826 x MAD) over them
  float photo_spread = 0.0f;             // of the photo's log luminance over them
};

// An exposure within this of another is taken to be the same: closer is an
// estimate's own error (a mirror ball's rim), a camera's exposure steps are
// a third of a stop (26 %).
constexpr float kExposureTolerance = 0.05f;

// Whether an exposure ratio lies outside 1 +- kExposureTolerance in some channel.
inline bool exposure_differs(const Vec3& ratio) {
  return ratio.array().log().abs().maxCoeff() >= std::log(1.0f + kExposureTolerance);
}

// Every pixel multiplied by `factor`, per channel: an image brought to
// another exposure (a probe to the photo's, a photo to the probe's).
inline void apply_exposure(Image& image, const Vec3& factor) {
  for (Vec3& p : image.pixels) p = p.cwiseProduct(factor);
}

// Fewer shared points than this fix no exposure.
constexpr size_t kMinExposurePoints = 100;

// A probe in the scene shows what the photo shows, shadows and textures
// alike: the ratio photo / probe varies far less over the shared points than
// the photo does. An environment image that was never taken in the scene (a
// Blender world's HDRI, exported as a probe at the camera) shows something
// else there, and its ratio varies as much as the photo: no exposure is read
// from it. The reference scenes' probes leave 0.28 of the photo's spread
// (outdoor, the least varied) or under 0.05; an HDRI, all of it.
constexpr float kMaxUnexplainedSpread = 0.5f;

// A surface point a probe and the photo both show cleanly: the probe pixel's
// whole square on one flat piece of one surface, seen by the camera from the
// same side at `pixel`, fully covered and not clipped there.
struct SharedPoint {
  SurfacePoint point;
  size_t pixel;  // the photo's (gbuffer's) pixel that shows it
  Vec3 probe;    // the probe pixel's radiance, positive
};

// The points `probe` shares with the photo, read every so many probe pixels
// each way that at most about kMaxSharedProbePixels are tried (9 rays each:
// a median or a fit needs no more than a few hundred thousand).
constexpr double kMaxSharedProbePixels = 262144.0;
std::vector<SharedPoint> points_shared_with_photo(const Probe& probe, const Scene& scene, const RayScene& rays,
                                                  const GBuffer& gbuffer);

// The exposure of `photo` against the probe named `probe_name` over the
// points they share (points_shared_with_photo). Nothing where they share
// fewer than kMinExposurePoints surface points, or the probe does not show
// them as the photo does (kMaxUnexplainedSpread).
std::optional<ProbeExposure> photo_exposure_from(const std::vector<SharedPoint>& shared, const Image& photo,
                                                 const std::string& probe_name);

}  // namespace relight
