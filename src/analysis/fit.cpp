#include "analysis/fit.h"

#include <fmt/format.h>
#include <spdlog/spdlog.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <optional>

#include "analysis/color_chart.h"
#include "analysis/photo_radiance.h"
#include "analysis/photo_units.h"
#include "analysis/probe_cleanup.h"
#include "analysis/probe_exposure.h"
#include "analysis/probe_lights.h"
#include "analysis/surface_albedo.h"
#include "analysis/view_checks.h"
#include "render/direct_light.h"

namespace relight {

namespace {

// One unknown or known term of the illumination: an image at unit emission.
struct Basis {
  Image image;
  Image indirect;  // the part of image that is not straight from the lights (environment, bounce light)
  bool known = false;
  Vec3 emission = Vec3::Zero();  // the known value, or the current estimate
};

IlluminationParts render_basis(const RayScene& rays, const GBuffer& gbuffer, Lighting lighting,
                               const SurfaceAlbedo& bounce, const KnownRadiance& known, const FitOptions& options,
                               Progress& progress) {
  IntegratorOptions integrator_options;
  integrator_options.max_bounces = options.max_bounces;
  const Integrator integrator(rays, lighting, &bounce, integrator_options, &known);
  IlluminationOptions illumination;
  illumination.paths_per_pixel = options.paths_per_pixel;
  illumination.seed = options.seed;
  return render_illumination_parts(gbuffer, integrator, illumination, progress, "fit: light transport");
}

// The bounce light off what the photo (or a probe) shows is the radiance it
// shows there, whatever lit it (PhotoRadiance): the fit renders it once, as
// a basis of known emission 1, and each light's and the background's basis
// only what bounces off the rest. A path of those ends dark where the photo
// shows the point it reaches.
class ShownAsDark final : public KnownRadiance {
 public:
  explicit ShownAsDark(const PhotoRadiance& shown) : shown_(shown) {}
  std::optional<Vec3> at(const SurfacePoint& p) const override {
    if (shown_.at(p)) return Vec3::Zero();
    return std::nullopt;
  }

 private:
  const PhotoRadiance& shown_;
};

struct PixelPair {
  size_t p, q;
};

// A handful of pairs is a handful of noisy equations: the example room's soft
// lamp at 320x240 gives 2 to 55 of them a round, and they put the background
// at 1.5 to 3 times its value. A round with fewer than this solves nothing.
constexpr size_t kMinEdgePairs = 200;

// Nearby pixels (a few apart) on one plane, fully covered, where the
// share of the lights in the illumination differs: across a shadow edge.
// (The light bounced off what the photo shows counts with the lights': most
// of it is theirs.)
// (Pairs across a bend — the facets of a column — would also test the shading
// model; a cast shadow on a plane tests only the light.)
// Pixels the photo clipped (Scene::photo_clipped) take part in no pair.
std::vector<PixelPair> shadow_edge_pairs(const GBuffer& g, const std::vector<Basis>& bases, size_t background,
                                         const std::vector<uint8_t>& clipped) {
  const int w = g.width(), h = g.height();
  std::vector<float> light_share(size_t(w) * h, 0.0f);
  for (size_t i = 0; i < light_share.size(); ++i) {
    float lights = 0.0f, total = 0.0f;
    for (size_t k = 0; k < bases.size(); ++k) {
      const float v = luminance(bases[k].image.pixels[i].cwiseProduct(bases[k].emission));
      total += v;
      if (k != background) lights += v;
    }
    light_share[i] = total > 0.0f ? lights / total : 0.0f;
  }
  std::vector<PixelPair> pairs;
  constexpr int kGap = 5;  // wider than a penumbra: compare fully lit with fully shadowed
  constexpr float kMinShareJump = 0.5f;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      if (g.coverage(x, y) < 1.0f) continue;
      for (const auto& [dx, dy] : {std::pair{kGap, 0}, std::pair{0, kGap}}) {
        const int nx = x + dx, ny = y + dy;
        if (nx >= w || ny >= h || g.coverage(nx, ny) < 1.0f || !g.same_surface(x, y, nx, ny)) continue;
        if (g.central(x, y).surface.normal.dot(g.central(nx, ny).surface.normal) < 0.999f) continue;
        const size_t p = size_t(y) * w + x, q = size_t(ny) * w + nx;
        if (clipped.size() == light_share.size() && (clipped[p] || clipped[q])) continue;
        if (std::abs(light_share[p] - light_share[q]) > kMinShareJump) pairs.push_back({p, q});
      }
    }
  return pairs;
}

// Solves the edge equations of one colour channel for the unknown emissions by
// iteratively reweighted least squares (Cauchy weights: texture edges that
// happen to lie along a shadow edge are outliers).
void solve_channel(const Image& photo, std::vector<Basis>& bases, const std::vector<PixelPair>& pairs, int c) {
  std::vector<size_t> unknown;
  for (size_t k = 0; k < bases.size(); ++k)
    if (!bases[k].known) unknown.push_back(k);
  if (unknown.empty() || pairs.empty()) return;
  const auto illum = [&](size_t i) {
    float sum = 0.0f;
    for (const auto& b : bases) sum += b.image.pixels[i][c] * b.emission[c];
    return sum;
  };
  const Eigen::Index m = Eigen::Index(pairs.size()), n = Eigen::Index(unknown.size());
  Eigen::MatrixXd A(m, n);
  Eigen::VectorXd rhs(m), scale(m);
  for (Eigen::Index r = 0; r < m; ++r) {
    const size_t p = pairs[r].p, q = pairs[r].q;
    const double fp = photo.pixels[p][c], fq = photo.pixels[q][c];
    scale[r] = 1.0 / std::max(1e-9, fp * illum(q) + fq * illum(p));  // makes each equation relative
    rhs[r] = 0.0;
    for (size_t k = 0; k < bases.size(); ++k) {
      const double coeff = fp * bases[k].image.pixels[q][c] - fq * bases[k].image.pixels[p][c];
      if (bases[k].known) rhs[r] -= coeff * bases[k].emission[c];
    }
    for (Eigen::Index j = 0; j < n; ++j)
      A(r, j) = fp * bases[unknown[j]].image.pixels[q][c] - fq * bases[unknown[j]].image.pixels[p][c];
  }
  Eigen::VectorXd weight = scale, x;
  for (int iteration = 0; iteration < 5; ++iteration) {
    x = (weight.asDiagonal() * A).colPivHouseholderQr().solve(weight.asDiagonal() * rhs);
    const Eigen::VectorXd residual = (scale.asDiagonal() * (A * x - rhs)).cwiseAbs();
    std::vector<double> sorted(residual.data(), residual.data() + m);
    std::nth_element(sorted.begin(), sorted.begin() + m / 2, sorted.end());
    const double sigma = std::max(1e-9, 1.4826 * sorted[m / 2]) * 2.0;
    for (Eigen::Index r = 0; r < m; ++r) weight[r] = scale[r] / (1.0 + std::pow(residual[r] / sigma, 2));
  }
  for (Eigen::Index j = 0; j < n; ++j) bases[unknown[j]].emission[c] = float(std::max(0.0, x[j]));
}

void scale_probe(Probe& probe, const Vec3& factor) {
  probe.scale = probe.scale.cwiseProduct(factor);
  apply_exposure(probe.image, factor);
}

// Whether the whole of the light (its disc, rectangle or sun disc: 3 x 3
// points over it) is in plain view from the probe's position: a probe the
// geometry hides the light from shows a wall or a reflection where the light
// should be, and measuring that would set the light to almost nothing.
bool probe_sees_light(const RayScene& rays, const Probe& probe, const Light& light) {
  const LightSampler sampler(light);
  const Vec3 towards = light.type == LightType::directional ? Vec3(-light.direction.normalized())
                                                            : Vec3((light.position - probe.position).normalized());
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const LightSample s = sampler.sample(probe.position, towards, Vec2((i + 0.5f) / 3, (j + 0.5f) / 3));
      const float tmax = std::isfinite(s.distance) ? s.distance * (1.0f - 1e-4f) : s.distance;
      if (rays.occluded(probe.position, s.direction, tmax)) return false;
    }
  return true;
}

// Where the probes see a light: each probe that sees it unoccluded, and the
// light's region in it.
struct ProbeSighting {
  const Probe* probe;
  LightInProbe seen;
};
std::vector<ProbeSighting> probe_sightings(const RayScene& rays, const std::vector<Probe>& probes,
                                           const Light& light) {
  std::vector<ProbeSighting> sightings;
  for (const Probe& probe : probes) {
    if (!probe_sees_light(rays, probe, light)) {
      spdlog::warn("{}: the geometry hides light \"{}\" from this probe's position: the light is not measured from it",
                   probe.path, light.name);
      continue;
    }
    if (auto seen = locate_light_in_probe(probe, light)) sightings.push_back({&probe, std::move(*seen)});
  }
  return sightings;
}

// The line from the probe through where it sees the light. The probe
// measures the middle of what a light fills, not its centre: the line is
// turned by how far apart the two are where it passes nearest the light as
// given (a slanted rectangle's near half fills more of the view).
SightLine line_of_sight(const ProbeSighting& sighting, const Light& given) {
  SightLine line{sighting.probe->position, sighting.seen.direction, std::nullopt, std::nullopt};
  Light near = given;
  near.position = line.nearest_to(given.position);
  const Vec3 centre = (near.position - line.origin).normalized();
  line.direction = (line.direction + centre - seen_middle(near, line.origin)).normalized();
  return line;
}

// How far along `line` the light's size puts it (distance_from_apparent_size),
// where that agrees with where it was given (sizes_agree): further
// off, the size given or the place is wrong (warn_about_the_view says so),
// and the photo places it.
std::optional<float> distance_from_size(const ProbeSighting& sighting, const Light& given, const SightLine& line) {
  const auto distance = distance_from_apparent_size(*sighting.probe, given, sighting.seen, line.direction);
  if (!distance) return std::nullopt;
  const float given_distance = (line.nearest_to(given.position) - line.origin).norm();
  if (!sizes_agree(given_distance / *distance)) {
    spdlog::info("light \"{}\": its size puts it {:.2f} m from probe {}, its place {:.2f} m: placed from the photo",
                 given.name, *distance, sighting.probe->path, given_distance);
    return std::nullopt;
  }
  return distance;
}

// The emission that gives what the probes saw (their mean) with the light
// where `light` has it: a lamp placed farther from the probe must be brighter
// to deliver the same irradiance there.
std::optional<Vec3> emission_from_sightings(const std::vector<ProbeSighting>& sightings, const Light& light) {
  Vec3 sum = Vec3::Zero();
  int n = 0;
  for (const ProbeSighting& s : sightings)
    if (const auto e = emission_from_probe(*s.probe, light, s.seen)) sum += *e, ++n;
  if (n == 0) return std::nullopt;
  return Vec3(sum / float(n));
}

// The fit's state: one basis per enabled light, then the background; the
// bounce light's albedo; the result as it stands.
class LightingFit {
 public:
  // `photo`: the scene's, its vignetting divided out where it was found;
  // `units`: its units against the probes (photo_units.h).
  LightingFit(const Scene& scene, const Image& photo, const PhotoUnits& units, const RayScene& rays,
              const GBuffer& gbuffer, const FitOptions& options, Progress& progress)
      : scene_(scene),
        photo_(photo),
        rays_(rays),
        gbuffer_(gbuffer),
        options_(options),
        progress_(progress),
        bounce_albedo_(gbuffer.width(), gbuffer.height(), Vec3::Ones()) {
    result.scene = scene;
    result.background_before = scene.background;
    for (size_t p = 0; p < result.scene.probes.size(); ++p)
      match_probe_to_photo(result.scene.probes[p], units.probe_exposures[p]);
    for (const Probe& p : result.scene.probes) {
      std::optional<Probe> distant = remove_local_geometry_from_probe(p, rays);
      if (distant) distant_.push_back(*distant);
      // One that sees only the geometry still shows the lights.
      light_probes_.push_back(distant ? std::move(*distant) : p);
    }
    for (size_t i = 0; i < scene.lights.size(); ++i) {
      const Light& light = scene.lights[i];
      if (!light.enabled) continue;
      Basis b;
      b.emission = light.emission();
      FittedLight report{light.name, light.emission(), light.emission(), "shadows"};
      std::vector<ProbeSighting> sightings = probe_sightings(rays, light_probes_, light);
      if (const auto seen = emission_from_sightings(sightings, light)) {
        b.known = true;
        b.emission = *seen;
        report.source = "probe";
      } else {
        sightings.clear();
      }
      sightings_.push_back(std::move(sightings));
      light_index_.push_back(i);
      bases_.push_back(std::move(b));
      result.lights.push_back(report);
    }
    const bool anchored = std::any_of(bases_.begin(), bases_.end(), [](const Basis& b) { return b.known; });
    if (!anchored && !bases_.empty()) {
      bases_.front().known = true;  // the scale anchor: see fit.h
      result.lights.front().source = "kept (scale anchor)";
      if (!scene.reference)
        spdlog::warn(
            "{}: no probe measures a light, so the overall brightness of the lights and the albedo trade off "
            "(twice the power, half the albedo); light \"{}\" keeps the power given as the scale anchor",
            scene.path.string(), result.lights.front().name);
    }
    background_ = bases_.size();
    bases_.push_back(Basis{Image(), Image(), false, scene.background});
    shown_ = bases_.size();
    bases_.push_back(Basis{Image(), Image(), true, Vec3::Ones()});
    see_the_photo_radiance();
  }

  // Renders the bases with the lights where result.scene has them, solves the
  // edge equations, and recovers the albedo for the next round's bounce light.
  void round(int number) {
    const PhotoAlbedo bounce(scene_.camera, gbuffer_, bounce_albedo_, unseen_);
    const ShownAsDark elsewhere(*shown_radiance_);
    for (size_t k = 0; k < light_index_.size(); ++k) {
      Lighting lighting;
      lighting.lights = {unit_light(result.scene.lights[light_index_[k]])};
      render(bases_[k], lighting, bounce, elsewhere);
    }
    Lighting sky;
    sky.environment = Environment::constant(Vec3::Ones());
    render(bases_[background_], sky, bounce, elsewhere);
    render(bases_[shown_], Lighting{}, bounce, *shown_radiance_);

    const std::vector<PixelPair> pairs = shadow_edge_pairs(gbuffer_, bases_, background_, scene_.photo_clipped);
    result.edge_pairs = pairs.size();
    if (pairs.size() >= kMinEdgePairs) {
      for (int c = 0; c < 3; ++c) solve_channel(photo_, bases_, pairs, c);
      solved_ = true;
    }
    const char* fitted_from = solved_ ? "shadows" : "kept: too few shadow edges to fit from";
    result.background_source = fitted_from;
    for (size_t k = 0; k < light_index_.size(); ++k)
      if (!bases_[k].known) result.lights[k].source = fitted_from;
    const Vec3& bg = bases_[background_].emission;
    spdlog::info("fit round {}: {} shadow-edge pixel pairs, background {:.4f} {:.4f} {:.4f}", number, pairs.size(),
                 bg.x(), bg.y(), bg.z());

    const AlbedoImages albedo = fitted_albedo();
    // The albedo (it matters only where neither the photo nor a probe shows
    // a surface) overshoots and undershoots in turn (too little bounce light
    // makes it too bright, which makes too much): after the first round (and
    // the first after a light was resized), the next bounces off the mean of
    // the last two, as the analysis does.
    if (number == 1 || albedo_outdated_) {
      albedo_outdated_ = false;
      bounce_albedo_ = albedo.albedo;
      unseen_ = albedo.mean;
    } else {
      for (size_t i = 0; i < bounce_albedo_.size(); ++i)
        bounce_albedo_.pixels[i] = 0.5f * (bounce_albedo_.pixels[i] + albedo.albedo.pixels[i]);
      unseen_ = 0.5f * (unseen_ + albedo.mean);
    }
  }

  // The photo's exposure and white balance from the surfaces of known albedo
  // (Scene::reference): every emission scaled, per channel, so that the
  // albedo recovered on them is the one given (albedo and light trade off:
  // photo = albedo x light). With a chart's patches, the scale per channel
  // is the least-squares one over every pixel of every patch.
  void apply_reference() {
    if (!scene_.reference) return;
    const ReferencePixels reference = reference_pixels(*scene_.reference, gbuffer_, scene_.mesh);
    Vec3 recovered_x_known = Vec3::Zero(), known_squared = Vec3::Zero();
    std::vector<uint8_t> patch_seen(reference.patches, 0);
    for (const ReferencePixel& p : reference.pixels) {
      recovered_x_known += bounce_albedo_.pixels[p.pixel].cwiseProduct(p.albedo);
      known_squared += p.albedo.cwiseProduct(p.albedo);
      patch_seen[p.patch] = 1;
    }
    const size_t pixels = reference.pixels.size();
    const size_t patches_seen = size_t(std::count(patch_seen.begin(), patch_seen.end(), 1));
    const std::string what = reference.patches > 1             ? "the chart's patches cover"
                             : scene_.reference->object.empty() ? "the polygon covers"
                                                                : "object \"" + scene_.reference->object + "\" covers";
    if (pixels == 0 || recovered_x_known.minCoeff() <= 0.0f) {
      spdlog::warn("{}: /reference: {} no lit pixel of the geometry in view; the overall scale is kept",
                   scene_.path.string(), what);
      return;
    }
    if (reference.patches > 1)
      spdlog::info("{}: /reference: {} of the chart's {} patches on the geometry in view, {} pixels",
                   scene_.path.string(), patches_seen, reference.patches, pixels);
    const Vec3 ratio = recovered_x_known.cwiseQuotient(known_squared);
    // The light bounced off what the photo shows is the photo's: its scale
    // is the photo's whatever the lights'.
    for (size_t k = 0; k < bases_.size(); ++k)
      if (k != shown_) bases_[k].emission = bases_[k].emission.cwiseProduct(ratio);
    for (Vec3& a : bounce_albedo_.pixels) a = a.cwiseQuotient(ratio);
    for (Probe& p : result.scene.probes) scale_probe(p, ratio);
    unseen_ = unseen_.cwiseQuotient(ratio);
    result.reference_scale = ratio;
  }

  // On the albedo the fitted lighting gives as it now stands (the analysis
  // will find much the same).
  void check_albedo_above_one() {
    const AlbedoImages albedo = fitted_albedo();
    result.albedo_above_one = share_above_one(gbuffer_, albedo.albedo);
    warn_about_albedo_above_one(scene_.path.string(), gbuffer_, albedo.albedo, albedo.mean, "the fitted lighting");
  }

  // Soft light (a lamp indoors) casts too few sharp shadows to tell the
  // background from the lights, and the edge fit can land anywhere. The
  // probes measure the environment directly, but only the part of it they
  // see: where the edge fit disagrees with their mean radiance by more than a
  // factor of two, the probes' mean is taken instead.
  void check_background_against_probes() {
    if (distant_.empty()) return;
    Vec3 mean = Vec3::Zero();
    for (const Probe& p : distant_) mean += mean_radiance(remove_lights_from_probe(p, result.scene.lights));
    mean /= float(distant_.size());
    const float ratio = luminance(bases_[background_].emission) / std::max(1e-6f, luminance(mean));
    if (!solved_ || ratio < 0.5f || ratio > 2.0f) {
      bases_[background_].emission = mean;
      result.background_source = "probe mean (the shadows disagree)";
    }
  }

  // The probe brought to the photo's units (probe_exposure.h), so that the
  // lights measured from it and the environment it gives are in them too.
  static void match_probe_to_photo(Probe& probe, const std::optional<ProbeExposure>& exposure) {
    if (!exposure) {
      spdlog::info("{}: the probe shows too few of the photo's surfaces, or not as the photo does (an environment "
                   "image rather than a probe taken in the scene), to match their exposures; the probe is taken to "
                   "be in the photo's units",
                   probe.path);
      return;
    }
    const Vec3& k = exposure->photo_over_probe;
    if (!exposure_differs(k)) {
      spdlog::info("{}: the probe's exposure matches the photo's within {:.0f} % ({} surface points both show)",
                   probe.path, 100 * kExposureTolerance, exposure->points);
      return;
    }
    spdlog::info("{}: the photo shows the surfaces {:.3f} {:.3f} {:.3f} times as bright as the probe does ({} points); "
                 "the probe is scaled to the photo's units",
                 probe.path, k.x(), k.y(), k.z(), exposure->points);
    scale_probe(probe, k);
  }

  // A light the probes resolve whose size, where the light now is (placed,
  // or as given), the first of them shows over 1.5 times too large or too
  // small (sizes_agree): its size was wrong, not its place, and it takes the
  // size the probe shows. True where one was resized.
  bool resize_from_probes() {
    bool resized = false;
    for (size_t k = 0; k < light_index_.size(); ++k) {
      if (sightings_[k].empty()) continue;
      const ProbeSighting& sighting = sightings_[k].front();
      Light& light = result.scene.lights[light_index_[k]];
      const auto scale = size_seen_over_given(*sighting.probe, light, sighting.seen);
      if (!scale || sizes_agree(*scale)) continue;
      if (light.type == LightType::area)
        light.size *= *scale;
      else
        light.radius *= *scale;
      result.lights[k].size_scale = *scale;
      resized = albedo_outdated_ = true;
    }
    return resized;
  }

  // Writes the fitted emissions and background into the result.
  void publish() {
    for (size_t k = 0; k < light_index_.size(); ++k) {
      set_emission(result.scene.lights[light_index_[k]], bases_[k].emission);
      result.lights[k].emission_after = bases_[k].emission;
    }
    result.scene.background = result.background_after = bases_[background_].emission;
  }

  // The emission scene light `index` has placed as `placed` (light_placement.h).
  Vec3 emission_when_placed(size_t index, const Light& placed) const {
    const auto k = std::find(light_index_.begin(), light_index_.end(), index) - light_index_.begin();
    if (size_t(k) < sightings_.size())
      if (const auto e = emission_from_sightings(sightings_[size_t(k)], placed)) return *e;
    return placed.emission();
  }

  // The line from the first probe that measured light `index` through it;
  // where a second probe elsewhere sees it too, the point the two lines
  // pass nearest; and how far along it the light's size puts it.
  std::optional<SightLine> sight_line(size_t index) const {
    const auto k = std::find(light_index_.begin(), light_index_.end(), index) - light_index_.begin();
    if (size_t(k) >= sightings_.size() || sightings_[size_t(k)].empty()) return std::nullopt;
    const std::vector<ProbeSighting>& seen = sightings_[size_t(k)];
    const Light& given = scene_.lights[index];
    SightLine line = line_of_sight(seen.front(), given);
    line.distance = distance_from_size(seen.front(), given, line);
    for (size_t j = 1; j < seen.size() && !line.crossing; ++j) {
      const SightLine other = line_of_sight(seen[j], given);
      constexpr float kApartM = 0.1f;  // probes closer than this see the light along nearly one line
      if ((other.origin - line.origin).norm() > kApartM)
        line.crossing = triangulate(line.origin, line.direction, other.origin, other.direction);
    }
    return line;
  }

  // The lights moved or resized: the probes measured, their emission where
  // they now are and of the size they now have, and the probe pixels that
  // show them.
  void remeasure_emissions() {
    for (size_t k = 0; k < light_index_.size(); ++k)
      if (const auto e = emission_from_sightings(sightings_[k], result.scene.lights[light_index_[k]]))
        bases_[k].emission = *e;
    see_the_photo_radiance();
  }

  // The illumination of the lighting fitted so far.
  Image illumination() const { return weighted_sum(&Basis::image); }
  // Its part not straight from the lights: the environment and bounce light.
  Image indirect_illumination() const { return weighted_sum(&Basis::indirect); }

  FitResult result;

 private:
  // The photo's and probes' radiance with the lights as they now are: the
  // probe pixels that show a light are not a wall's radiance.
  void see_the_photo_radiance() {
    shown_radiance_.emplace(scene_.camera, gbuffer_, photo_, result.scene.probes, rays_, result.scene.lights);
  }

  // The albedo the photo over the illumination fitted so far gives.
  AlbedoImages fitted_albedo() const {
    return recover_albedo(photo_, scene_.photo_clipped,
                          IlluminationImages{illumination(), Image(gbuffer_.width(), gbuffer_.height())}, gbuffer_);
  }

  void render(Basis& basis, const Lighting& lighting, const SurfaceAlbedo& bounce, const KnownRadiance& known) {
    IlluminationParts parts = render_basis(rays_, gbuffer_, lighting, bounce, known, options_, progress_);
    basis.image = parts.total();
    basis.indirect = std::move(parts.indirect);
  }

  // The sum over the bases of their part `image`, each at its emission.
  Image weighted_sum(Image Basis::*image) const {
    Image sum(gbuffer_.width(), gbuffer_.height());
    for (size_t i = 0; i < sum.size(); ++i)
      for (const auto& b : bases_) sum.pixels[i] += (b.*image).pixels[i].cwiseProduct(b.emission);
    return sum;
  }

  const Scene& scene_;
  const Image& photo_;  // what the lights are fitted to
  const RayScene& rays_;
  const GBuffer& gbuffer_;
  const FitOptions& options_;
  Progress& progress_;
  std::vector<Probe> distant_;       // the probes without the modelled geometry (those that see past it)
  std::vector<Probe> light_probes_;  // each probe, without the geometry where it sees past it
  std::vector<size_t> light_index_;  // basis k is result.scene.lights[light_index_[k]]
  std::vector<std::vector<ProbeSighting>> sightings_;  // basis k's light in the probes (none: not measured)
  std::vector<Basis> bases_;
  size_t background_ = 0;  // the background's basis
  size_t shown_ = 0;       // the basis of the light bounced off what the photo and probes show
  std::optional<PhotoRadiance> shown_radiance_;  // holds references to result.scene.probes
  Image bounce_albedo_;    // the last round's albedo (at first: white)
  Vec3 unseen_ = Vec3::Ones();
  bool solved_ = false;  // a round had enough shadow edges to solve for the unknowns
  bool albedo_outdated_ = false;  // the last albedo's lights were resized: the next round's replaces it
};

}  // namespace

std::vector<std::string> describe_fit(const FitResult& fit) {
  const auto change = [](const std::string& what, const Vec3& before, const Vec3& after, const std::string& source) {
    return fmt::format("{} {:.4g} {:.4g} {:.4g} -> {:.4g} {:.4g} {:.4g} ({})", what, before.x(), before.y(), before.z(),
                       after.x(), after.y(), after.z(), source);
  };
  std::vector<std::string> lines;
  for (const FittedLight& l : fit.lights) {
    lines.push_back(change(fmt::format("{:<16} emission", l.name), l.emission_before, l.emission_after, l.source));
    if (l.size_scale != 1.0f)
      lines.push_back(
          fmt::format("{:<16} size x {:.3g} (what the probe shows it fill where it is)", l.name, l.size_scale));
  }
  lines.push_back(
      change(fmt::format("{:<16}", "background"), fit.background_before, fit.background_after, fit.background_source));
  for (const PlacedLight& p : fit.placement) {
    const float moved = p.moved_m(), turned = p.turned_deg();
    std::string line = fmt::format("{:<16}", p.name);
    if (moved > 0.0f)
      line += fmt::format(" moved {:.3g} m to {:.4g} {:.4g} {:.4g}", moved, p.position_after.x(), p.position_after.y(),
                          p.position_after.z());
    if (turned > 0.0f)
      line += fmt::format(" turned {:.3g} degrees to {:.4g} {:.4g} {:.4g}", turned, p.direction_after.x(),
                          p.direction_after.y(), p.direction_after.z());
    if (moved == 0.0f && turned == 0.0f) line += " stays where it was";
    lines.push_back(line + fmt::format(" (shadow mismatch {:.4f} -> {:.4f})", p.objective_before, p.objective_after));
  }
  lines.push_back(fmt::format("{} shadow-edge pixel pairs", fit.edge_pairs));
  return lines;
}

void set_emission(Light& light, const Vec3& emission) {
  const float colour_luminance = std::max(1e-6f, luminance(light.color));
  const float strength = luminance(emission) / colour_luminance;
  if (strength <= 0.0f) return;
  light.color = emission / strength;
  (light.type == LightType::directional ? light.irradiance : light.power) = strength;
}

FitResult fit_lighting(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const FitOptions& options,
                       Progress& progress) {
  constexpr int kPlacementPasses = 2;
  // The lights are fitted to the photo without its lens's vignetting, as the
  // analysis divides it: a falloff towards the corners is shading across
  // whole walls, and a closed room's floor lamp in its true place was moved
  // 32 cm to explain a falloff of 35 %. The fitted scene keeps the photo.
  const PhotoUnits units = photo_units_against_the_probes(scene, rays, gbuffer, options.keep_vignetting);
  std::optional<Image> devignetted;
  if (units.vignetting) remove_vignetting(devignetted.emplace(scene.photo), *units.vignetting);
  const Image& photo = devignetted ? *devignetted : scene.photo;
  LightingFit fit(scene, photo, units, rays, gbuffer, options, progress);
  for (int round = 1; round <= options.rounds; ++round) fit.round(round);
  fit.check_background_against_probes();
  fit.publish();

  // Lights moved to where their shadows fall, then their emission fitted
  // again: a shadow edge in the wrong place misleads the edge equations.
  // The bounce light is held fixed while the lights move, as it was where
  // they were given: once they have moved, it is rendered again from where
  // they are, and they are placed once more against it.
  if (options.refine_placement) {
    const EmissionOfPlaced emission_of = [&fit](size_t index, const Light& placed) {
      return fit.emission_when_placed(index, placed);
    };
    // Once for both passes: a light's line and its warnings do not change.
    std::vector<std::optional<SightLine>> sight_lines;
    for (size_t i = 0; i < scene.lights.size(); ++i) sight_lines.push_back(fit.sight_line(i));
    const SightLineOf sight_line_of = [&sight_lines](size_t index) { return sight_lines[index]; };
    for (int pass = 0; pass < kPlacementPasses; ++pass) {
      std::vector<PlacedLight> placed =
          refine_light_placement(fit.result.scene, photo, rays, gbuffer, fit.indirect_illumination(), emission_of,
                                 sight_line_of, options.placement, progress);
      const bool moved = std::any_of(placed.begin(), placed.end(),
                                     [](const PlacedLight& p) { return p.moved_m() > 0.0f || p.turned_deg() > 0.0f; });
      if (pass > 0 && !moved) break;
      if (pass == 0) {
        fit.result.placement = std::move(placed);
      } else {
        for (size_t k = 0; k < placed.size(); ++k) {
          PlacedLight& total = fit.result.placement[k];
          total.position_after = placed[k].position_after;
          total.direction_after = placed[k].direction_after;
          total.objective_after = placed[k].objective_after;
        }
      }
      if (moved) fit.remeasure_emissions();  // else as they were measured
      fit.round(options.rounds + 1 + pass);
      fit.check_background_against_probes();
      fit.publish();
      if (!moved) break;
    }
  }
  // A light resized (its emission, measured by the probes, follows its size)
  // is fitted twice more, its shadows rendered at that size: the first
  // round's bounce light is still that of the albedo the old size gave, the
  // second's that of the first's.
  if (fit.resize_from_probes()) {
    fit.remeasure_emissions();
    for (int round = 1; round <= 2; ++round) fit.round(options.rounds + kPlacementPasses + round);
    fit.check_background_against_probes();
    fit.publish();
  }
  fit.apply_reference();
  fit.publish();
  fit.check_albedo_above_one();
  return fit.result;
}

}  // namespace relight
