#include "analysis/light_placement.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <array>
#include <cmath>
#include <functional>

#include "render/direct_light.h"

namespace relight {

namespace {

// Per pixel, radiance or illumination in colour. The comparison is made per
// channel: photo = albedo x illumination holds in each channel, and only
// there does the albedo cancel from a ratio. (In luminance it does not where
// lights of two colours meet on a coloured wall: a warm lamp and a neutral
// panel on a sage wall gave a ratio the search moved both lights 50 cm for.)
using Colours = std::vector<Vec3>;

// Pixel pairs a gap apart, right and down, both fully covered and on one
// plane (a shadow edge across a bend would also test the shading model).
struct PlanePairs {
  std::vector<uint32_t> p, q;
  std::vector<Vec3> photo_log_ratio;  // log(photo(p) / photo(q)), per channel
};

bool on_one_plane(const SurfacePoint& a, const SurfacePoint& b) {
  return a.geometric_normal.dot(b.geometric_normal) > 0.999f &&
         std::abs(a.geometric_normal.dot(a.position - b.position)) < 0.002f * a.distance;
}

PlanePairs plane_pairs(const GBuffer& g, const Colours& photo, int gap) {
  PlanePairs pairs;
  const int w = g.width(), h = g.height();
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (g.coverage(x, y) < 1.0f || !g.central(x, y).hit || photo[i].minCoeff() <= 0.0f) continue;
      for (const auto& [dx, dy] : {std::pair{gap, 0}, std::pair{0, gap}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx >= w || ny >= h || g.coverage(nx, ny) < 1.0f || !g.central(nx, ny).hit) continue;
        const size_t j = size_t(ny) * w + nx;
        if (photo[j].minCoeff() <= 0.0f || !on_one_plane(g.central(x, y).surface, g.central(nx, ny).surface))
          continue;
        pairs.p.push_back(uint32_t(i));
        pairs.q.push_back(uint32_t(j));
        pairs.photo_log_ratio.push_back(photo[i].cwiseQuotient(photo[j]).array().log().matrix());
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
float pair_mismatch(const PlanePairs& pairs, size_t k, const Colours& illumination) {
  constexpr float kCap = 1.0f, kDark = 1e-6f;
  const Vec3 lp = illumination[pairs.p[k]].cwiseMax(kDark), lq = illumination[pairs.q[k]].cwiseMax(kDark);
  const Vec3 r = (pairs.photo_log_ratio[k] - Vec3(lp.cwiseQuotient(lq).array().log().matrix())).cwiseAbs();
  return r.cwiseMin(kCap).mean();
}

double mismatch(const PlanePairs& pairs, const Colours& illumination) {
  double sum = 0.0;
  for (size_t k = 0; k < pairs.p.size(); ++k) sum += pair_mismatch(pairs, k, illumination);
  return pairs.p.empty() ? 0.0 : sum / double(pairs.p.size());
}

// The image cut into kBlocks x kBlocks blocks: neighbouring pixels share
// texture, so the evidence of a change is not independent pixel by pixel
// but, roughly, block by block.
constexpr int kBlocks = 8;
size_t block_of(uint32_t pixel, int width, int height) {
  const int x = int(pixel % uint32_t(width)), y = int(pixel / uint32_t(width));
  return size_t(y * kBlocks / height) * kBlocks + size_t(x * kBlocks / width);
}

// How many standard errors `after` lowers the mismatch by: the spread of the
// blocks' mean changes gives the standard error of their mean.
double improvement_in_standard_errors(const PlanePairs& pairs, const Colours& before, const Colours& after, int width,
                                      int height) {
  std::vector<double> change(kBlocks * kBlocks, 0.0);
  std::vector<int> count(kBlocks * kBlocks, 0);
  for (size_t k = 0; k < pairs.p.size(); ++k) {
    const size_t b = block_of(pairs.p[k], width, height);
    change[b] += pair_mismatch(pairs, k, before) - pair_mismatch(pairs, k, after);
    ++count[b];
  }
  std::vector<double> means;
  for (size_t b = 0; b < change.size(); ++b)
    if (count[b] > 0) means.push_back(change[b] / count[b]);
  if (means.size() < 2) return 0.0;
  double mean = 0.0, square = 0.0;
  for (double m : means) mean += m;
  mean /= double(means.size());
  for (double m : means) square += (m - mean) * (m - mean);
  const double standard_error = std::sqrt(square / double(means.size() - 1) / double(means.size()));
  return standard_error > 0.0 ? mean / standard_error : 0.0;
}

// The view's planes: pixels fully covered, joined to their neighbours on one
// plane, each region at least 1/200 of the view (smaller ones are books'
// faces and facets, whose own albedo leaves little shading to compare).
std::vector<std::vector<uint32_t>> plane_regions(const GBuffer& g, const Colours& photo) {
  const int w = g.width(), h = g.height();
  const auto usable = [&](int x, int y) {
    return g.coverage(x, y) >= 1.0f && g.central(x, y).hit && photo[size_t(y) * w + x].minCoeff() > 0.0f;
  };
  std::vector<bool> taken(size_t(w) * h, false);
  std::vector<std::vector<uint32_t>> regions;
  std::vector<uint32_t> region, stack;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (taken[size_t(y) * w + x] || !usable(x, y)) continue;
      region.clear();
      stack.assign(1, uint32_t(y * w + x));
      taken[stack.back()] = true;
      while (!stack.empty()) {
        const uint32_t i = stack.back();
        stack.pop_back();
        region.push_back(i);
        const int cx = int(i % uint32_t(w)), cy = int(i / uint32_t(w));
        for (const auto& [dx, dy] : {std::pair{1, 0}, std::pair{-1, 0}, std::pair{0, 1}, std::pair{0, -1}}) {
          const int nx = cx + dx, ny = cy + dy;
          if (nx < 0 || ny < 0 || nx >= w || ny >= h || taken[size_t(ny) * w + nx] || !usable(nx, ny) ||
              !on_one_plane(g.central(cx, cy).surface, g.central(nx, ny).surface))
            continue;
          taken[size_t(ny) * w + nx] = true;
          stack.push_back(uint32_t(ny * w + nx));
        }
      }
      if (region.size() * 200 >= size_t(w) * h) regions.push_back(region);
    }
  return regions;
}

// How many standard errors better `after` explains the photo's shading
// across whole planes than `before`: the lamp's falloff over a wall, which
// the pairs' mismatch sees a few per cent of where a light is weak (a floor
// lamp 20 cm off lowered it by 0.2 %). Per plane and colour channel, the
// log albedo `before` gives (log photo/before) is regressed on the log
// change `after` makes (log after/before), one intercept per plane: the
// plane's own albedo. A slope of 1 says the photo is shaded as `after`
// has it, 0 as `before`; over 1/2, `after` leaves the smaller squared
// error. The result is (slope - 1/2) over its standard error, clustered by
// block (each block's residual sum: texture is correlated within a block).
double shading_in_standard_errors(const std::vector<std::vector<uint32_t>>& regions, const Colours& photo,
                                  const Colours& before, const Colours& after, int width, int height) {
  constexpr float kDark = 1e-6f;
  std::vector<double> xy(kBlocks * kBlocks, 0.0), xx(kBlocks * kBlocks, 0.0);
  std::vector<double> x, y;
  for (const auto& region : regions)
    for (int c = 0; c < 3; ++c) {
      x.clear(), y.clear();
      double mean_x = 0.0, mean_y = 0.0;
      for (const uint32_t i : region) {
        const double b = std::max(before[i][c], kDark);
        x.push_back(std::log(std::max(after[i][c], kDark) / b));
        y.push_back(std::log(photo[i][c] / b));
        mean_x += x.back(), mean_y += y.back();
      }
      mean_x /= double(region.size()), mean_y /= double(region.size());
      for (size_t k = 0; k < region.size(); ++k) {
        const size_t b = block_of(region[k], width, height);
        xy[b] += (x[k] - mean_x) * (y[k] - mean_y);
        xx[b] += (x[k] - mean_x) * (x[k] - mean_x);
      }
    }
  double sum_xy = 0.0, sum_xx = 0.0;
  for (size_t b = 0; b < xy.size(); ++b) sum_xy += xy[b], sum_xx += xx[b];
  if (sum_xx <= 0.0) return 0.0;
  const double slope = sum_xy / sum_xx;
  double variance = 0.0;
  for (size_t b = 0; b < xy.size(); ++b) variance += (xy[b] - slope * xx[b]) * (xy[b] - slope * xx[b]);
  const double standard_error = std::sqrt(variance) / sum_xx;
  return standard_error > 0.0 ? (slope - 0.5) / standard_error : 0.0;
}

// What the photo says of a change of placement, two ways: the shadow edges
// (pairs a gap apart) and the shading across whole planes.
struct Evidence {
  const PlanePairs& pairs;
  std::vector<std::vector<uint32_t>> regions;
  const Colours& photo;
  int width, height;

  struct Standing {
    double shadows, shading;  // standard errors by which `after` is better
    double best() const { return std::max(shadows, shading); }
  };
  Standing of(const Colours& before, const Colours& after) const {
    return {improvement_in_standard_errors(pairs, before, after, width, height),
            shading_in_standard_errors(regions, photo, before, after, width, height)};
  }
};

// The light at a point of its search space, in units of the first steps:
// an offset of its position (point, spot, area) and a turn of its direction
// about two axes across it (sun, spot, area).
class LightPlacement {
 public:
  static constexpr int kMaxDimensions = 5;
  using Point = std::array<float, kMaxDimensions>;

  LightPlacement(const Light& light, const std::optional<SightLine>& sight, const RayScene& rays,
                 const PlacementOptions& options)
      : light_(light),
        sight_(moves() ? sight : std::nullopt),
        metres_(options.position_step),
        degrees_(options.direction_step_deg) {
    const Vec3 d = light.direction.normalized();
    across_u_ = d.unitOrthogonal();
    across_v_ = d.cross(across_u_);
    SurfacePoint hit;
    if (keeps_aim() && rays.intersect(light.position, d, hit)) aim_distance_ = hit.distance;
    aimed_from_ = light.position;
    // On the sight line, from where a second probe sees it or else the point
    // of it nearest the given place.
    if (sight_) light_.position = sight_->start_for(light.position);
  }
  bool moves() const { return light_.type != LightType::directional; }
  // Where the probe's view of its size puts it: it is not moved from there.
  bool placed_by_probe() const { return sight_ && sight_->distance; }
  bool turns() const { return light_.type != LightType::point; }
  // A spot that moves keeps pointing where it pointed: moving it then shifts
  // its shadows, turning it its cone, and the two do not trade off along a
  // valley the search would crawl. An area light has no cone: moved, it
  // keeps facing the way it faced (a ceiling panel given 20 cm off and tilted
  // back towards its old aim as it moved was found nowhere near).
  bool keeps_aim() const { return light_.type == LightType::spot; }
  int dimensions() const { return position_dimensions() + (turns() ? 2 : 0); }
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
      l.position += metres_ * (sight_ ? Vec3(x[axis] * sight_->direction) : Vec3(x[axis], x[axis + 1], x[axis + 2]));
      if (keeps_aim()) l.direction = (aimed_from_ + aim_distance_ * turned / turned.dot(d) - l.position).normalized();
    }
    return l;
  }

 private:
  // A light a probe sees moves along its sight line only: the probe fixes
  // its direction from there to a pixel, far closer than the photo's
  // shading does across a closed room; the photo gives the distance, unless
  // the light's size seen gives it (to a centimetre or two in the public
  // scenes, where the photo's shading in a closed room misled by 13-19 cm).
  int position_dimensions() const { return !moves() || placed_by_probe() ? 0 : sight_ ? 1 : 3; }

  Light light_;
  std::optional<SightLine> sight_;
  float metres_, degrees_;
  Vec3 across_u_, across_v_;
  float aim_distance_ = 1.0f;  // m, along the direction to what a spot points at
  Vec3 aimed_from_;            // where it was given, pointing there
};

// The illumination `rest` and the lights' `direct` light give together.
Colours with_direct(Colours rest, const std::vector<Colours>& direct) {
  for (const Colours& d : direct)
    for (size_t i = 0; i < rest.size(); ++i) rest[i] += d[i];
  return rest;
}

// The lights being placed together: where each stands in its search space,
// its direct light there, and the illumination all of them give with the rest.
// Moving one light re-renders only that light's direct light.
class Placements {
 public:
  Placements(std::vector<LightPlacement> lights, std::vector<Colours> direct, Colours rest,
             const std::function<Colours(size_t, const Light&)>& direct_of)
      : lights_(std::move(lights)),
        direct_(std::move(direct)),
        x_(lights_.size()),
        total_(with_direct(std::move(rest), direct_)),
        direct_of_(direct_of) {}

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
  const Colours& illumination() const { return total_; }
  size_t size() const { return lights_.size(); }
  const LightPlacement& placement(size_t light) const { return lights_[light]; }
  const LightPlacement::Point& at(size_t light) const { return x_[light]; }
  Light light(size_t k) const { return lights_[k].at(x_[k]); }

  // The illumination with light k at x instead, and its direct light there.
  std::pair<Colours, Colours> trial(size_t k, const LightPlacement::Point& x) const {
    Colours direct = direct_of_(k, lights_[k].at(x));
    Colours total = total_;
    for (size_t i = 0; i < total.size(); ++i) total[i] += direct[i] - direct_[k][i];
    return {std::move(total), std::move(direct)};
  }
  void move(size_t k, const LightPlacement::Point& x, Colours total, Colours direct) {
    x_[k] = x, total_ = std::move(total), direct_[k] = std::move(direct);
  }

 private:
  std::vector<LightPlacement> lights_;
  std::vector<Colours> direct_;
  std::vector<LightPlacement::Point> x_;
  Colours total_;
  std::function<Colours(size_t, const Light&)> direct_of_;  // light k placed so
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

// A light that moved and turned keeps its turn only where the turn alone
// lowers the mismatch by `significant` standard errors: carried along by the
// move's significance, a ceiling panel brought back to within a centimetre
// of its place was also tilted 2.9 degrees, for nothing the photo shows
// clearly, and its albedo lost 1.4 dB by the tilt.
void keep_only_significant_turns(Placements& placements, const Evidence& evidence, double significant) {
  for (size_t k = 0; k < placements.size(); ++k) {
    LightPlacement::Point untilted = placements.at(k);
    if (!placements.placement(k).moves() || !placements.placement(k).turns() ||
        (untilted[0] == 0.0f && untilted[1] == 0.0f))
      continue;
    untilted[0] = untilted[1] = 0.0f;
    auto [total, direct] = placements.trial(k, untilted);
    const Evidence::Standing turn = evidence.of(total, placements.illumination());
    if (turn.best() >= significant) continue;
    spdlog::info(
        "fit: {}'s turn matches the shadows better by {:.1f} and the shading by {:.1f} standard errors only: it is "
        "not turned",
        placements.light(k).name, turn.shadows, turn.shading);
    placements.move(k, untilted, std::move(total), std::move(direct));
  }
}

}  // namespace

float PlacedLight::moved_m() const { return (position_after - position_before).norm(); }

float PlacedLight::turned_deg() const { return angle_degrees(direction_before, direction_after); }

Vec3 SightLine::nearest_to(const Vec3& p) const {
  constexpr float kNearest = 0.05f;  // m: a light is not placed inside the probe
  return origin + std::max(kNearest, (p - origin).dot(direction)) * direction;
}

std::vector<PlacedLight> refine_light_placement(Scene& scene, const Image& photo_image, const RayScene& rays,
                                                const GBuffer& gbuffer, const Image& indirect,
                                                const EmissionOfPlaced& emission_of, const SightLineOf& sight_line_of,
                                                const PlacementOptions& options, Progress& progress) {
  const PixelSurfaces surfaces = PixelSurfaces::central_samples(gbuffer);
  const Colours& photo = photo_image.pixels;

  std::vector<size_t> enabled;
  for (size_t i = 0; i < scene.lights.size(); ++i)
    if (scene.lights[i].enabled) enabled.push_back(i);

  // The k-th enabled light's direct light, placed as `light`, with the
  // emission it has there.
  const auto direct_of = [&](size_t k, const Light& light) {
    DirectLightSettings settings;
    settings.light_samples = LightSampler(light).needs_random() ? options.light_samples : 1;
    // A soft light's falloff exact, noise only in its penumbrae: noise left in
    // the rest at the given place would hold the light there.
    settings.exact_unshadowed = true;
    Image unit;
    render_direct_light(surfaces, rays, unit_light(light), settings, unit);
    const Vec3 emission = emission_of(enabled[k], light);
    Colours lit(unit.size());
    for (size_t i = 0; i < lit.size(); ++i) lit[i] = unit.pixels[i].x() * emission;  // a white light's is grey
    return lit;
  };
  // The search starts where each light was given, or, for one a probe sees,
  // on its sight line (SightLine::start_for). Where it finds nothing
  // better, each light is kept where it was given, or where a probe's view
  // of its size puts it.
  std::vector<LightPlacement> searched;
  std::vector<Light> kept;
  std::vector<Colours> given_direct, direct;
  for (size_t k = 0; k < enabled.size(); ++k) {
    const Light& light = scene.lights[enabled[k]];
    const std::optional<SightLine> sight = sight_line_of(enabled[k]);
    searched.emplace_back(light, sight, rays, options);
    const Light first = searched.back().at({});
    kept.push_back(searched.back().placed_by_probe() ? first : light);
    given_direct.push_back(direct_of(k, kept.back()));
    direct.push_back(first.position == kept.back().position ? given_direct.back() : direct_of(k, first));
    if (searched.back().placed_by_probe())
      spdlog::info(
          "fit: {} is placed where its size fills what a probe sees, {:.2f} m from the probe ({:.1f} cm from "
          "where it was given)",
          light.name, (first.position - sight->origin).norm(), 100.0f * (first.position - light.position).norm());
    else if (first.position != light.position)
      spdlog::info(
          "fit: {} is searched for along the line a probe sees it along, from {:.1f} cm from where it was "
          "given",
          light.name, 100.0f * (first.position - light.position).norm());
  }
  const Colours given = with_direct(indirect.pixels, given_direct);  // the lights where they are kept

  struct Level {
    int gap;
    float first_step, last_step;  // in units of the options' first steps
  };
  constexpr Level kLevels[] = {{16, 1.0f, 1.0f / 8}, {4, 1.0f / 16, 1.0f / 64}};
  std::vector<PlanePairs> pairs;
  for (const Level& level : kLevels) pairs.push_back(plane_pairs(gbuffer, photo, level.gap));

  Placements placements(searched, direct, indirect.pixels, direct_of);
  int dimensions = 0;
  for (const auto& l : searched) dimensions += l.dimensions();
  const int max_evaluations = options.evaluations_per_dimension * dimensions;
  progress.begin("fit: placing the lights", max_evaluations);
  int evaluations = 0;
  for (size_t level = 0; level < std::size(kLevels); ++level)
    coordinate_search(placements, pairs[level], kLevels[level].first_step, kLevels[level].last_step, evaluations,
                      max_evaluations, progress);
  progress.end();

  // The narrow gap sees noise the wide one averages out, and a flat
  // objective lets a light wander far for nothing: the lights are kept (as
  // given, or where a probe placed them) unless the placement found matches
  // the photo better by kSignificant standard errors, in the wide gap's
  // shadow mismatch or in the shading across whole planes. (In a closed room
  // a lamp in its true place was moved 30 cm for a fall of 0.3 %, under one
  // standard error; and a lamp whose sight line runs along the room's wall is
  // placed on it no better. A weak lamp moves the shadow mismatch little and
  // the shading across its walls more: a floor lamp brought back 19 cm along
  // its sight line stood 0.9 standard errors by its shadows, 3.0 by shading.)
  constexpr double kSignificant = 2.0;
  const Evidence evidence{pairs.front(), plane_regions(gbuffer, photo), photo, gbuffer.width(), gbuffer.height()};
  const double before = mismatch(pairs.front(), given);
  double after = mismatch(pairs.front(), placements.illumination());
  const Evidence::Standing found = evidence.of(given, placements.illumination());
  const bool stay = found.best() < kSignificant;
  if (stay) {
    if (after < before) {
      std::string moves;
      for (size_t k = 0; k < enabled.size(); ++k)
        moves += fmt::format("; {} {:.1f} cm away", scene.lights[enabled[k]].name,
                             100.0f * (placements.light(k).position - scene.lights[enabled[k]].position).norm());
      spdlog::info(
          "fit: the lights' best placement matches the shadows better by {:.1f} ({:.4f} -> {:.4f}) and the "
          "shading by {:.1f} standard errors only{}: they stay",
          found.shadows, before, after, found.shading, moves);
    }
    after = before;
  } else {
    spdlog::info(
        "fit: the lights' placement found matches the shadows better by {:.1f} and the shading by {:.1f} "
        "standard errors",
        found.shadows, found.shading);
    keep_only_significant_turns(placements, evidence, kSignificant);
    after = mismatch(pairs.front(), placements.illumination());
  }

  std::vector<PlacedLight> placed;
  for (size_t k = 0; k < enabled.size(); ++k) {
    Light& light = scene.lights[enabled[k]];
    PlacedLight report;
    report.name = light.name;
    report.position_before = light.position;
    report.direction_before = light.direction.normalized();
    report.objective_before = before;
    report.objective_after = after;
    light = stay ? kept[k] : placements.light(k);
    report.position_after = light.position;
    report.direction_after = light.direction.normalized();
    spdlog::info("fit: {} moved {:.3g} m, turned {:.3g} degrees (shadow mismatch {:.4f} -> {:.4f})", light.name,
                 report.moved_m(), report.turned_deg(), before, after);
    placed.push_back(report);
  }
  return placed;
}

}  // namespace relight
