#include "analysis/light_placement.h"

#include <spdlog/spdlog.h>

#include <array>
#include <cmath>
#include <functional>

#include "render/direct_light.h"

namespace relight {

namespace {

constexpr float kDegree = 3.14159265f / 180.0f;

// Pixel pairs a gap apart, right and down, both fully covered and on one
// plane (a shadow edge across a bend would also test the shading model).
struct PlanePairs {
  std::vector<uint32_t> p, q;
  std::vector<float> photo_log_ratio;  // log(photo(p) / photo(q)), luminance
};

bool on_one_plane(const SurfacePoint& a, const SurfacePoint& b) {
  return a.geometric_normal.dot(b.geometric_normal) > 0.999f &&
         std::abs(a.geometric_normal.dot(a.position - b.position)) < 0.002f * a.distance;
}

PlanePairs plane_pairs(const GBuffer& g, const std::vector<float>& photo, int gap) {
  PlanePairs pairs;
  const int w = g.width(), h = g.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (g.coverage(x, y) < 1.0f || !g.central(x, y).hit || photo[i] <= 0.0f) continue;
      for (const auto& [dx, dy] : {std::pair{gap, 0}, std::pair{0, gap}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx >= w || ny >= h || g.coverage(nx, ny) < 1.0f || !g.central(nx, ny).hit) continue;
        const size_t j = size_t(ny) * w + nx;
        if (photo[j] <= 0.0f || !on_one_plane(g.central(x, y).surface, g.central(nx, ny).surface)) continue;
        pairs.p.push_back(uint32_t(i));
        pairs.q.push_back(uint32_t(j));
        pairs.photo_log_ratio.push_back(std::log(photo[i] / photo[j]));
      }
    }
  return pairs;
}

// The mean penalty over the pairs of the illumination `light` against the
// photo: |log ratio difference| less a dead zone, capped.
double mismatch(const PlanePairs& pairs, const std::vector<float>& illumination) {
  constexpr float kDeadZone = 0.1f, kCap = 1.0f, kDark = 1e-6f;
  double sum = 0.0;
  for (size_t k = 0; k < pairs.p.size(); ++k) {
    const float lp = std::max(kDark, illumination[pairs.p[k]]), lq = std::max(kDark, illumination[pairs.q[k]]);
    const float r = std::abs(pairs.photo_log_ratio[k] - std::log(lp / lq));
    sum += std::min(std::max(r - kDeadZone, 0.0f), kCap);
  }
  return pairs.p.empty() ? 0.0 : sum / double(pairs.p.size());
}

std::vector<float> luminance_of(const Image& image) {
  std::vector<float> y(image.size());
  for (size_t i = 0; i < y.size(); ++i) y[i] = luminance(image.pixels[i]);
  return y;
}

// The light at a point of its search space: an offset of its position in
// metres, or a turn of its direction in degrees about two axes across it.
class LightPlacement {
 public:
  explicit LightPlacement(const Light& light) : light_(light) {
    if (is_sun()) {
      const Vec3 d = light.direction.normalized();
      across_u_ = d.unitOrthogonal();
      across_v_ = d.cross(across_u_);
    }
  }
  bool is_sun() const { return light_.type == LightType::directional; }
  int dimensions() const { return is_sun() ? 2 : 3; }
  Light at(const std::array<float, 3>& x) const {
    Light l = light_;
    if (is_sun())
      l.direction = (light_.direction.normalized() + std::tan(x[0] * kDegree) * across_u_ +
                     std::tan(x[1] * kDegree) * across_v_)
                        .normalized();
    else
      l.position = light_.position + Vec3(x[0], x[1], x[2]);
    return l;
  }

 private:
  Light light_;
  Vec3 across_u_ = Vec3::Zero(), across_v_ = Vec3::Zero();
};

// Compass search: tries a step each way along each axis, moves to the first
// better point, halves the step when none is better, until the step is below
// `min_step` or the evaluations run out.
struct SearchState {
  std::array<float, 3> x{0, 0, 0};
  double value = 0.0;
  int evaluations = 0;
};

void compass_search(SearchState& s, int dimensions, float step, float min_step, int max_evaluations,
                    const std::function<double(const std::array<float, 3>&)>& objective) {
  while (step >= min_step && s.evaluations < max_evaluations) {
    bool moved = false;
    for (int axis = 0; axis < dimensions && !moved && s.evaluations < max_evaluations; ++axis)
      for (const float sign : {1.0f, -1.0f}) {
        std::array<float, 3> y = s.x;
        y[size_t(axis)] += sign * step;
        const double v = objective(y);
        ++s.evaluations;
        if (v < s.value) {
          s.x = y, s.value = v, moved = true;
          break;
        }
        if (s.evaluations >= max_evaluations) break;
      }
    if (!moved) step *= 0.5f;
  }
}

}  // namespace

std::vector<PlacedLight> refine_light_placement(Scene& scene, const RayScene& rays, const GBuffer& gbuffer,
                                                const Image& illumination, const PlacementOptions& options,
                                                Progress& progress) {
  const PixelSurfaces surfaces = PixelSurfaces::central_samples(gbuffer);
  const std::vector<float> photo = luminance_of(scene.photo);
  const std::vector<float> total = luminance_of(illumination);

  // Each light's direct light at unit emission, where it stands now.
  const auto direct_of = [&](const Light& light) {
    DirectLightSettings settings;
    settings.light_samples = LightSampler(light).needs_random() ? options.light_samples : 1;
    Image unit;
    render_direct_light(surfaces, rays, unit_light(light), settings, unit);
    const float strength = luminance(light.emission());
    std::vector<float> y(unit.size());
    for (size_t i = 0; i < y.size(); ++i) y[i] = strength * unit.pixels[i].x();  // a white light's is grey
    return y;
  };
  std::vector<size_t> enabled;
  std::vector<std::vector<float>> direct;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].enabled) enabled.push_back(i), direct.push_back(direct_of(scene.lights[i]));

  // What does not move with the lights: the illumination less their direct light.
  std::vector<float> rest = total;
  for (const auto& d : direct)
    for (size_t i = 0; i < rest.size(); ++i) rest[i] -= d[i];
  for (float& r : rest) r = std::max(r, 0.0f);

  struct Level {
    int gap;
    float first_step, last_step;  // relative to the options' first step
  };
  constexpr Level kLevels[] = {{16, 1.0f, 1.0f / 8}, {4, 1.0f / 16, 1.0f / 64}};
  std::vector<PlanePairs> pairs;
  for (const Level& level : kLevels) pairs.push_back(plane_pairs(gbuffer, photo, level.gap));

  std::vector<PlacedLight> placed;
  for (size_t k = 0; k < enabled.size(); ++k) {
    Light& light = scene.lights[enabled[k]];
    const LightPlacement placement(light);
    const float step = placement.is_sun() ? options.direction_step_deg : options.position_step;
    // The illumination with light k where the search puts it.
    std::vector<float> others = rest;
    for (size_t j = 0; j < enabled.size(); ++j)
      if (j != k)
        for (size_t i = 0; i < others.size(); ++i) others[i] += direct[j][i];
    const auto illumination_at = [&](const std::array<float, 3>& x) {
      std::vector<float> l = direct_of(placement.at(x));
      for (size_t i = 0; i < l.size(); ++i) l[i] += others[i];
      return l;
    };

    progress.begin("fit: placing " + light.name, options.max_evaluations);
    PlacedLight report;
    report.name = light.name;
    report.direction = placement.is_sun();
    report.before = placement.is_sun() ? light.direction.normalized() : light.position;
    SearchState state;
    for (size_t level = 0; level < std::size(kLevels); ++level) {
      const auto objective = [&](const std::array<float, 3>& x) {
        progress.advance();
        return mismatch(pairs[level], illumination_at(x));
      };
      state.value = objective(state.x);
      ++state.evaluations;
      if (level == 0) report.objective_before = state.value;
      compass_search(state, placement.dimensions(), step * kLevels[level].first_step,
                     step * kLevels[level].last_step, options.max_evaluations, objective);
    }
    progress.end();
    // The narrow gap sees noise the wide one averages out: where its optimum is
    // worse on the wide gap than the start, the light stays.
    report.objective_after = mismatch(pairs.front(), illumination_at(state.x));
    if (report.objective_after >= report.objective_before) state.x = {0, 0, 0};
    report.objective_after = std::min(report.objective_after, report.objective_before);
    light = placement.at(state.x);
    direct[k] = direct_of(light);
    if (placement.is_sun()) {
      report.after = light.direction.normalized();
      report.moved = std::acos(std::clamp(report.before.dot(report.after), -1.0f, 1.0f)) / kDegree;
    } else {
      report.after = light.position;
      report.moved = (report.after - report.before).norm();
    }
    spdlog::info("fit: {} moved {:.3g} {} (shadow mismatch {:.4f} -> {:.4f})", light.name, report.moved,
                 report.direction ? "degrees" : "m", report.objective_before, report.objective_after);
    placed.push_back(report);
  }
  return placed;
}

}  // namespace relight
