#include "analysis/light_placement.h"

#include <spdlog/spdlog.h>

#include <array>
#include <cmath>
#include <functional>

#include "render/direct_light.h"

namespace relight {

namespace {

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

// The mean penalty over the pairs of the illumination against the photo:
// |log ratio difference|, capped (a pair across an albedo edge counts the
// same however strong the edge). No dead zone: in a closed room a lamp's
// shadows are soft against the light its walls send back, and what tells
// 20 cm apart is mostly the falloff across each surface, a few per cent per
// pair, which a dead zone of 0.1 threw away (the lamp then stayed 15 cm off).
double mismatch(const PlanePairs& pairs, const std::vector<float>& illumination) {
  constexpr float kCap = 1.0f, kDark = 1e-6f;
  double sum = 0.0;
  for (size_t k = 0; k < pairs.p.size(); ++k) {
    const float lp = std::max(kDark, illumination[pairs.p[k]]), lq = std::max(kDark, illumination[pairs.q[k]]);
    const float r = std::abs(pairs.photo_log_ratio[k] - std::log(lp / lq));
    sum += std::min(r, kCap);
  }
  return pairs.p.empty() ? 0.0 : sum / double(pairs.p.size());
}

std::vector<float> luminance_of(const Image& image) {
  std::vector<float> y(image.size());
  for (size_t i = 0; i < y.size(); ++i) y[i] = luminance(image.pixels[i]);
  return y;
}

// The light at a point of its search space, in units of the first steps:
// an offset of its position (point, spot, area) and a turn of its direction
// about two axes across it (sun, spot, area). A spot or area light that moves
// keeps pointing at the surface it pointed at: moving it then shifts its
// shadows, turning it its cone, and the two do not trade off against each
// other along a valley the search would crawl.
class LightPlacement {
 public:
  static constexpr int kMaxDimensions = 5;
  using Point = std::array<float, kMaxDimensions>;

  LightPlacement(const Light& light, const RayScene& rays, const PlacementOptions& options)
      : light_(light), metres_(options.position_step), degrees_(options.direction_step_deg) {
    const Vec3 d = light.direction.normalized();
    across_u_ = d.unitOrthogonal();
    across_v_ = d.cross(across_u_);
    SurfacePoint hit;
    if (moves() && turns() && rays.intersect(light.position, d, hit)) aim_distance_ = hit.distance;
  }
  bool moves() const { return light_.type != LightType::directional; }
  bool turns() const { return light_.type != LightType::point; }
  int dimensions() const { return (moves() ? 3 : 0) + (turns() ? 2 : 0); }
  bool is_turn(size_t axis) const { return turns() && axis < 2; }

  Light at(const Point& x) const {
    Light l = light_;
    const Vec3 d = light_.direction.normalized();
    Vec3 turned = d;
    if (turns()) {
      turned = (d + std::tan(radians(x[0] * degrees_)) * across_u_ + std::tan(radians(x[1] * degrees_)) * across_v_)
                   .normalized();
      l.direction = turned;
    }
    if (moves()) {
      const size_t axis = turns() ? 2 : 0;
      l.position += metres_ * Vec3(x[axis], x[axis + 1], x[axis + 2]);
      if (turns()) l.direction = (light_.position + aim_distance_ * turned / turned.dot(d) - l.position).normalized();
    }
    return l;
  }

 private:
  Light light_;
  float metres_, degrees_;
  Vec3 across_u_, across_v_;
  float aim_distance_ = 1.0f;  // m, along the direction to what the light points at
};

// The lights being placed together: where each stands in its search space,
// its direct light there, and the illumination all of them give with the rest.
// Moving one light re-renders only that light's direct light.
class Placements {
 public:
  Placements(std::vector<LightPlacement> lights, std::vector<std::vector<float>> direct, std::vector<float> rest,
             const std::function<std::vector<float>(const Light&)>& direct_of)
      : lights_(std::move(lights)),
        direct_(std::move(direct)),
        x_(lights_.size()),
        total_(std::move(rest)),
        direct_of_(direct_of) {
    for (const auto& d : direct_)
      for (size_t i = 0; i < total_.size(); ++i) total_[i] += d[i];
  }

  // Every search axis as (light, axis of its space), the lights' turns first:
  // a spot's cone, the widest edge it makes, is set by where it points.
  std::vector<std::pair<size_t, size_t>> axes() const {
    std::vector<std::pair<size_t, size_t>> a;
    for (const bool turns : {true, false})
      for (size_t k = 0; k < lights_.size(); ++k)
        for (int i = 0; i < lights_[k].dimensions(); ++i)
          if (lights_[k].is_turn(size_t(i)) == turns) a.emplace_back(k, size_t(i));
    return a;
  }
  const std::vector<float>& illumination() const { return total_; }
  const LightPlacement::Point& at(size_t light) const { return x_[light]; }
  Light light(size_t k) const { return lights_[k].at(x_[k]); }

  // The illumination with light k at x instead, and its direct light there.
  std::pair<std::vector<float>, std::vector<float>> trial(size_t k, const LightPlacement::Point& x) const {
    std::vector<float> direct = direct_of_(lights_[k].at(x));
    std::vector<float> total = total_;
    for (size_t i = 0; i < total.size(); ++i) total[i] += direct[i] - direct_[k][i];
    return {std::move(total), std::move(direct)};
  }
  void move(size_t k, const LightPlacement::Point& x, std::vector<float> total, std::vector<float> direct) {
    x_[k] = x, total_ = std::move(total), direct_[k] = std::move(direct);
  }

 private:
  std::vector<LightPlacement> lights_;
  std::vector<std::vector<float>> direct_;
  std::vector<LightPlacement::Point> x_;
  std::vector<float> total_;
  std::function<std::vector<float>(const Light&)> direct_of_;
};

// Coordinate search: tries a step each way along each axis in turn and moves
// to the first better point, starting again from the first axis; when no
// axis gives a better point the step halves, until it is below `min_step` or
// the evaluations run out. (Jumping on along the last move, as Hooke and
// Jeeves do, overshot a spot's valley; keeping on through the axes after a
// move drifted a lamp's soft shadows 3 cm.)
void coordinate_search(Placements& placements, const PlanePairs& pairs, float step, float min_step, int& evaluations,
                       int max_evaluations, Progress& progress) {
  const auto axes = placements.axes();
  double value = mismatch(pairs, placements.illumination());
  while (step >= min_step && evaluations < max_evaluations) {
    bool improved = false;
    for (size_t a = 0; a < axes.size() && !improved; ++a)
      for (const float sign : {1.0f, -1.0f}) {
        if (evaluations >= max_evaluations) return;
        const auto [k, axis] = axes[a];
        LightPlacement::Point x = placements.at(k);
        x[axis] += sign * step;
        auto [total, direct] = placements.trial(k, x);
        const double v = mismatch(pairs, total);
        ++evaluations;
        progress.advance();
        if (v < value) {
          placements.move(k, x, std::move(total), std::move(direct));
          value = v, improved = true;
          break;
        }
      }
    if (!improved) step *= 0.5f;
  }
}

}  // namespace

float PlacedLight::moved_m() const { return (position_after - position_before).norm(); }

float PlacedLight::turned_deg() const { return angle_degrees(direction_before, direction_after); }

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
    float first_step, last_step;  // in units of the options' first steps
  };
  constexpr Level kLevels[] = {{16, 1.0f, 1.0f / 8}, {4, 1.0f / 16, 1.0f / 64}};
  std::vector<PlanePairs> pairs;
  for (const Level& level : kLevels) pairs.push_back(plane_pairs(gbuffer, photo, level.gap));

  std::vector<LightPlacement> searched;
  for (const size_t i : enabled) searched.emplace_back(scene.lights[i], rays, options);
  Placements placements(searched, direct, rest, direct_of);
  const Placements start = placements;
  int dimensions = 0;
  for (const auto& l : searched) dimensions += l.dimensions();
  const int max_evaluations = options.evaluations_per_dimension * dimensions;
  progress.begin("fit: placing the lights", max_evaluations);
  int evaluations = 0;
  for (size_t level = 0; level < std::size(kLevels); ++level)
    coordinate_search(placements, pairs[level], kLevels[level].first_step, kLevels[level].last_step, evaluations,
                      max_evaluations, progress);
  progress.end();

  // The narrow gap sees noise the wide one averages out: where its optimum is
  // worse on the wide gap than the start, the lights stay.
  const double before = mismatch(pairs.front(), start.illumination());
  double after = mismatch(pairs.front(), placements.illumination());
  if (after >= before) placements = start, after = before;

  std::vector<PlacedLight> placed;
  for (size_t k = 0; k < enabled.size(); ++k) {
    Light& light = scene.lights[enabled[k]];
    PlacedLight report;
    report.name = light.name;
    report.position_before = light.position;
    report.direction_before = light.direction.normalized();
    report.objective_before = before;
    report.objective_after = after;
    light = placements.light(k);
    report.position_after = light.position;
    report.direction_after = light.direction.normalized();
    spdlog::info("fit: {} moved {:.3g} m, turned {:.3g} degrees (shadow mismatch {:.4f} -> {:.4f})", light.name,
                 report.moved_m(), report.turned_deg(), before, after);
    placed.push_back(report);
  }
  return placed;
}

}  // namespace relight
