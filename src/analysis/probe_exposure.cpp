#include "analysis/probe_exposure.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <spdlog/spdlog.h>

#include "core/statistics.h"

namespace relight {

namespace {

// The surface point a probe pixel shows, where the pixel's whole square
// (3 x 3 directions over it) shows the same flat piece of one surface: a
// pixel across a silhouette or a crease mixes two radiances.
std::optional<SurfacePoint> surface_seen_cleanly(const Probe& probe, const ProbeFrame& frame, const RayScene& rays,
                                                 int x, int y) {
  const int w = probe.image.width, h = probe.image.height;
  std::optional<SurfacePoint> centre;
  for (int k : {4, 0, 1, 2, 3, 5, 6, 7, 8}) {  // the centre first
    const Vec2 uv((float(x) + 0.5f * float(k % 3)) / float(w), (float(y) + 0.5f * float(k / 3)) / float(h));
    const auto d = probe_uv_to_direction(probe.mapping, frame, uv);
    SurfacePoint hit;
    if (!d || !rays.intersect(probe.position, *d, hit)) return std::nullopt;
    if (!centre) {
      centre = hit;
      continue;
    }
    const bool same_plane = hit.geometric_normal.dot(centre->geometric_normal) > 0.99f &&
                            std::abs(hit.distance - centre->distance) < 0.05f * centre->distance;
    if (!same_plane) return std::nullopt;
  }
  return centre;
}

// The photo pixel that shows `point` (seen from the probe), if the camera
// sees that very point from the same side of its surface, fully covered and
// not clipped.
std::optional<size_t> photo_pixel_showing(const Scene& scene, const GBuffer& gbuffer, const Vec3& probe_position,
                                          const SurfacePoint& point) {
  const auto xy = scene.camera.project(point.position);
  if (!xy) return std::nullopt;
  const int x = int(std::floor(xy->x())), y = int(std::floor(xy->y()));
  if (x < 0 || y < 0 || x >= gbuffer.width() || y >= gbuffer.height() || gbuffer.coverage(x, y) < 1.0f)
    return std::nullopt;
  const size_t i = size_t(y) * gbuffer.width() + x;
  if (i < scene.photo_clipped.size() && scene.photo_clipped[i]) return std::nullopt;
  const SurfacePoint seen = gbuffer.central(x, y).surface;
  const float camera_distance = (point.position - scene.camera.position()).norm();
  if ((seen.position - point.position).norm() > 0.01f * camera_distance) return std::nullopt;  // hidden
  const Vec3& n = point.geometric_normal;
  const bool same_side =
      n.dot(probe_position - point.position) * n.dot(scene.camera.position() - point.position) > 0.0f;
  if (!same_side) return std::nullopt;
  return i;
}

}  // namespace

std::vector<SharedPoint> points_shared_with_photo(const Probe& probe, const Scene& scene, const RayScene& rays,
                                                  const GBuffer& gbuffer) {
  const ProbeFrame frame(probe.forward, probe.up);
  const int stride = std::max(1, int(std::ceil(std::sqrt(double(probe.image.size()) / kMaxSharedProbePixels))));
  std::vector<SharedPoint> shared;
  for (int y = 0; y < probe.image.height; y += stride)
    for (int x = 0; x < probe.image.width; x += stride) {
      const Vec3& shown = probe.image.at(x, y);
      if (shown.minCoeff() <= 0.0f) continue;
      const auto point = surface_seen_cleanly(probe, frame, rays, x, y);
      if (!point) continue;
      if (const auto pixel = photo_pixel_showing(scene, gbuffer, probe.position, *point))
        shared.push_back({*point, *pixel, shown});
    }
  return shared;
}

std::optional<ProbeExposure> photo_exposure_from(const std::vector<SharedPoint>& shared, const Image& photo_image,
                                                 const std::string& probe_name) {
  std::array<std::vector<double>, 3> log_ratio;
  std::vector<double> log_luminance_ratio, log_photo;
  for (const SharedPoint& s : shared) {
    const Vec3& photo = photo_image.pixels[s.pixel];
    if (photo.minCoeff() <= 0.0f) continue;
    for (int c = 0; c < 3; ++c) log_ratio[c].push_back(std::log(double(photo[c]) / double(s.probe[c])));
    log_luminance_ratio.push_back(std::log(double(luminance(photo)) / double(luminance(s.probe))));
    log_photo.push_back(std::log(double(luminance(photo))));
  }
  if (log_luminance_ratio.size() < kMinExposurePoints) return std::nullopt;
  ProbeExposure exposure;
  exposure.points = log_luminance_ratio.size();
  for (int c = 0; c < 3; ++c) exposure.photo_over_probe[c] = float(std::exp(percentile(log_ratio[c], 0.5)));
  const double middle = percentile(log_luminance_ratio, 0.5);
  for (double& r : log_luminance_ratio) r = std::abs(r - middle);
  exposure.spread = float(1.4826 * percentile(log_luminance_ratio, 0.5));
  const double photo_middle = percentile(log_photo, 0.5);
  for (double& l : log_photo) l = std::abs(l - photo_middle);
  exposure.photo_spread = float(1.4826 * percentile(log_photo, 0.5));
  if (!(exposure.spread < kMaxUnexplainedSpread * exposure.photo_spread)) {
    spdlog::info(
        "{}: over the {} surface points it shares with the photo, photo / probe varies by {:.3f} against "
        "the photo's {:.3f}: it does not show them as the photo does",
        probe_name, exposure.points, exposure.spread, exposure.photo_spread);
    return std::nullopt;
  }
  return exposure;
}

}  // namespace relight
