#include "analysis/view_checks.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "core/image.h"
#include "io/image_io.h"
#include "render/direct_light.h"

namespace relight {

namespace {

constexpr float kMinShareInView = 0.05f;  // of the photo
constexpr float kUnitRatio = 50.0f;    // depth against the lights' distances
// The share of the surfaces in view whose albedo may exceed 1 (noise,
// highlights) before the lighting is said to be too weak.
constexpr double kMaxShareAboveOne = 0.01;

float median(std::vector<float> values) {
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

void warn_about_coverage(const Scene& scene, const GBuffer& gbuffer) {
  const auto& c = gbuffer.coverage();
  const float share = std::accumulate(c.begin(), c.end(), 0.0f) / float(c.size());
  if (share < kMinShareInView)
    spdlog::warn(
        "{}: the geometry covers {:.1f} % of the photo (the rest is taken as background); check the camera "
        "and the geometry's units",
        scene.geometry_path.string(), 100.0f * share);
}

// The unit a factor of about `ratio` suggests, geometry against scene.json.
const char* likely_unit(float ratio) {
  if (ratio > 300.0f) return "the geometry in millimetres";
  if (ratio > 1.0f) return "the geometry in centimetres (or inches)";
  if (ratio > 1.0f / 300.0f) return "the lights and camera in centimetres, or the geometry in decimetres";
  return "the lights and camera in millimetres";
}

void warn_about_depth(const Scene& scene, const PixelSurfaces& view) {
  std::vector<float> depths, anchors;
  for (size_t i = 0; i < view.surface.size(); ++i)
    if (view.hit[i]) depths.push_back(view.surface[i].distance);
  const Vec3& eye = scene.camera.position();
  for (const Light& l : scene.lights)
    if (l.type != LightType::directional) anchors.push_back((l.position - eye).norm());
  for (const Probe& p : scene.probes) anchors.push_back((p.position - eye).norm());
  if (depths.empty() || anchors.empty()) return;
  const float depth = median(depths), anchor = std::max(median(anchors), 1e-6f), ratio = depth / anchor;
  if (ratio < kUnitRatio && ratio > 1.0f / kUnitRatio) return;
  spdlog::warn(
      "{}: the geometry the camera sees lies {:.3g} from it, the lights and probes {:.3g}: {:.0f} times "
      "{}; is {}? relight's unit is the metre",
      scene.geometry_path.string(), depth, anchor, ratio > 1 ? ratio : 1 / ratio, ratio > 1 ? "as far" : "nearer",
      likely_unit(ratio));
}

void warn_about_unseen_lights(const Scene& scene, const RayScene& rays, const PixelSurfaces& view) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    if (!light.enabled || light.emission().isZero()) continue;  // said when loaded
    Image direct;
    render_direct_light(view, rays, unit_light(light), DirectLightSettings{}, direct);
    if (is_black(direct))
      spdlog::warn(
          "{}: /lights/{}{}: lights nothing the camera sees (every surface in view is behind it, outside "
          "its cone or in shadow); check its position and direction",
          scene.path.string(), i, light.name.empty() ? "" : " (" + light.name + ")");
  }
}

}  // namespace

void warn_about_the_view(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer) {
  const PixelSurfaces view = PixelSurfaces::central_samples(gbuffer);
  warn_about_coverage(scene, gbuffer);
  warn_about_depth(scene, view);
  warn_about_unseen_lights(scene, rays, view);
}

void warn_about_albedo_above_one(const std::string& scene_file, const GBuffer& gbuffer, const Image& albedo,
                                 const Vec3& unseen, const char* lighting) {
  size_t covered = 0, above = 0;
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x) {
      if (gbuffer.coverage(x, y) < 1.0f) continue;
      ++covered;
      if (albedo.at(x, y).maxCoeff() > 1.0f) ++above;
    }
  const char* why = "the lights are too weak for the photo (a light missing, its power too low, or a probe forgotten)";
  if (covered > 0 && double(above) > kMaxShareAboveOne * double(covered))
    spdlog::warn("{}: with {} the albedo is above 1 on {:.1f} % of the surfaces in view: {}", scene_file, lighting,
                 100.0 * double(above) / double(covered), why);
  if (unseen.maxCoeff() > 1.0f)
    spdlog::warn("{}: with {} the surfaces the camera does not see take an albedo of {:.2f} {:.2f} {:.2f}, above 1: {}",
                 scene_file, lighting, unseen.x(), unseen.y(), unseen.z(), why);
}

}  // namespace relight
