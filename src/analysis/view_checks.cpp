#include "analysis/view_checks.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "analysis/probe_lights.h"
#include "core/image.h"
#include "core/sampling.h"
#include "io/image_io.h"
#include "render/direct_light.h"

namespace relight {

namespace {

constexpr float kMinShareInView = 0.05f;  // of the photo
constexpr float kUnitRatio = 50.0f;    // depth against the lights' distances
// The share of the surfaces in view whose albedo may exceed 1 (noise,
// highlights) before the lighting is said to be too weak.
constexpr double kMaxShareAboveOne = 0.01;
// Of a light's emitting surface, the share that may lie beyond the geometry
// (a sample's rounding at a wall it touches) before it is said to.
constexpr float kMaxShareBeyond = 0.05f;
constexpr int kGrid = 16;  // samples each way over a light's surface

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

std::string light_key(const Scene& scene, size_t i) {
  const Light& light = scene.lights[i];
  return "/lights/" + std::to_string(i) + (light.name.empty() ? "" : " (" + light.name + ")");
}

void warn_about_unseen_lights(const Scene& scene, const RayScene& rays, const PixelSurfaces& view) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    if (!light.enabled || light.emission().isZero()) continue;  // said when loaded
    Image direct;
    render_direct_light(view, rays, unit_light(light), DirectLightSettings{}, direct);
    if (is_black(direct))
      spdlog::warn(
          "{}: {}: lights nothing the camera sees (every surface in view is behind it, outside its cone or in "
          "shadow); check its position and direction",
          scene.path.string(), light_key(scene, i));
  }
}

// The share of the light's emitting surface (an area light's rectangle, a
// lamp's sphere) that a surface of the geometry cuts off from its centre:
// the part through a wall or a ceiling, whose light the room never gets.
float share_beyond_the_geometry(const Light& light, const RayScene& rays) {
  const bool rectangle = light.type == LightType::area;
  if (!rectangle && (light.type == LightType::directional || light.radius <= 0.0f)) return 0.0f;
  const AreaLightSides sides = rectangle ? area_light_sides(light) : AreaLightSides{};
  int beyond = 0;
  for (int i = 0; i < kGrid; ++i)
    for (int j = 0; j < kGrid; ++j) {
      const Vec2 u((i + 0.5f) / kGrid, (j + 0.5f) / kGrid);
      const Vec3 offset =
          rectangle ? Vec3((u.x() - 0.5f) * light.size.x() * sides.w + (u.y() - 0.5f) * light.size.y() * sides.h)
                    : Vec3(light.radius * sample_uniform_sphere(u));
      const float reach = offset.norm();
      beyond += reach > 0.0f && rays.occluded(light.position, offset / reach, reach);
    }
  return float(beyond) / float(kGrid * kGrid);
}

void warn_about_lights_through_the_geometry(const Scene& scene, const RayScene& rays) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    if (!light.enabled) continue;
    const float share = share_beyond_the_geometry(light, rays);
    if (share <= kMaxShareBeyond) continue;
    spdlog::warn(
        "{}: {}: {:.0f} % of its {} lies beyond a surface of the geometry (through a wall, the ceiling or an "
        "object), and its light there never reaches the room; check its size and position",
        scene.path.string(), light_key(scene, i), 100.0f * share,
        light.type == LightType::area ? "rectangle" : "sphere");
  }
}

// A light a probe resolves whose size given fills what the probe sees of it
// at a distance far from where it is: its size or its place is wrong.
void warn_about_sizes_the_probes_contradict(const Scene& scene) {
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const Light& light = scene.lights[i];
    for (const Probe& probe : scene.probes) {
      const auto seen = locate_light_in_probe(probe, light);
      if (!seen) continue;
      const auto scale = size_seen_over_given(probe, light, *seen);
      if (!scale) continue;
      if (!sizes_agree(*scale))
        spdlog::warn(
            "{}: {}: probe {} shows it {:.2g} times the size given: its size or its place is wrong; `relight fit` "
            "resizes it, with --refine-placement places it",
            scene.path.string(), light_key(scene, i), probe.path, *scale);
      break;  // the first probe that resolves it
    }
  }
}

}  // namespace

void warn_about_the_view(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer) {
  const PixelSurfaces view = PixelSurfaces::central_samples(gbuffer);
  warn_about_coverage(scene, gbuffer);
  warn_about_depth(scene, view);
  warn_about_unseen_lights(scene, rays, view);
  warn_about_lights_through_the_geometry(scene, rays);
  warn_about_sizes_the_probes_contradict(scene);
}

double share_above_one(const GBuffer& gbuffer, const Image& albedo) {
  size_t covered = 0, above = 0;
  for (int y = 0; y < gbuffer.height(); ++y)
    for (int x = 0; x < gbuffer.width(); ++x) {
      if (gbuffer.coverage(x, y) < 1.0f) continue;
      ++covered;
      if (albedo.at(x, y).maxCoeff() > 1.0f) ++above;
    }
  return covered > 0 ? double(above) / double(covered) : 0.0;
}

void warn_about_albedo_above_one(const std::string& scene_file, const GBuffer& gbuffer, const Image& albedo,
                                 const Vec3& unseen, const char* lighting) {
  const char* why = "the lights are too weak for the photo (a light missing, its power too low, or a probe forgotten)";
  if (const double above = share_above_one(gbuffer, albedo); above > kMaxShareAboveOne)
    spdlog::warn("{}: with {} the albedo is above 1 on {:.1f} % of the surfaces in view: {}", scene_file, lighting,
                 100.0 * above, why);
  if (unseen.maxCoeff() > 1.0f)
    spdlog::warn("{}: with {} the surfaces the camera does not see take an albedo of {:.2f} {:.2f} {:.2f}, above 1: {}",
                 scene_file, lighting, unseen.x(), unseen.y(), unseen.z(), why);
}

}  // namespace relight
