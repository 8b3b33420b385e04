#include "analysis/material_estimation.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <memory>
#include <set>

#include "analysis/photo_radiance.h"
#include "analysis/probe_exposure.h"
#include "analysis/strategy.h"
#include "core/error.h"
#include "core/statistics.h"
#include "render/specular.h"

namespace relight {

namespace {

// Huber's threshold in robust standard deviations (95 % efficiency on
// Gaussian noise).
constexpr float kHuber = 1.345f;
// The specular the highlights are predicted at (Principled's default): a
// fitted scale k is specular 0.5 k, and k = 2 (specular 1) all a
// dielectric can reflect.
constexpr float kDefaultSpecular = 0.5f;
// Below this specular a fitted highlight is too faint to matter: left matte.
constexpr float kMinSpecular = 0.05f;
// The pixel offsets the gradients are taken over: a sharp highlight shows
// at one pixel, a broad one over several.
constexpr int kSteps[] = {1, 2, 4};
// A broad sheen's steps, in parts of the view's width (a 40th, 20th and
// 10th: the scene's scale, whatever the photo's size), as far as the
// jackknife's blocks (jackknife_block: a tenth of the width).
constexpr int kBroadStepsPerWidth[] = {40, 20, 10};
// About the most pixels a broad fit takes as the first of its pairs (a
// larger view is sampled on a grid).
constexpr double kBroadPixels = 5e5;
// The most points of an object its two views are compared at, each costing
// the highlight's estimates both ways at every roughness.
constexpr size_t kMaxPointsSeenTwice = 16384;

float median_of(std::vector<float> v) {
  if (v.empty()) return 0.0f;
  const auto mid = v.begin() + std::ptrdiff_t(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

// A robust standard deviation: 1.4826 x the median absolute value.
float robust_sigma(const std::vector<float>& e) {
  std::vector<float> a(e.size());
  std::transform(e.begin(), e.end(), a.begin(), [](float x) { return std::abs(x); });
  return 1.4826f * median_of(std::move(a));
}

double huber_loss(const std::vector<float>& e, float threshold) {
  double sum = 0.0;
  for (const float x : e) {
    const double a = std::abs(x);
    sum += a < threshold ? 0.5 * a * a : threshold * (a - 0.5 * threshold);
  }
  return sum;
}

// What each whole pixel of the view shows, and how its photo compares with
// its illumination.
struct ViewPixels {
  std::vector<int32_t> object;  // per pixel: the object shown whole and unclipped, or -1
  std::vector<Vec3> colour;     // photo / illumination (the shading)
};

// The object every sample of pixel (x, y) sees where one does, all of it
// matte as the scene has it (a finely divided object's pixel sees several
// of its triangles).
std::optional<uint32_t> matte_object_seen_whole(const Scene& scene, const GBuffer& gbuffer, int x, int y,
                                                std::vector<GBufferSample>& samples) {
  if (const std::optional<uint32_t> t = gbuffer.single_triangle(x, y))
    return scene.gloss.at(*t) ? std::nullopt : std::optional(scene.mesh.triangle_objects[*t]);
  gbuffer.pixel_samples(x, y, samples);
  if (!samples[0].hit) return std::nullopt;
  const uint32_t object = scene.mesh.triangle_objects[samples[0].surface.prim];
  for (const GBufferSample& s : samples)
    if (!s.hit || scene.mesh.triangle_objects[s.surface.prim] != object || scene.gloss.at(s.surface.prim))
      return std::nullopt;
  return object;
}

ViewPixels view_pixels(const Scene& scene, const GBuffer& gbuffer, const Analysis& analysis, const Image& photo) {
  const int w = gbuffer.width(), h = gbuffer.height();
  ViewPixels v;
  v.object.assign(size_t(w) * h, -1);
  v.colour.assign(size_t(w) * h, Vec3::Zero());
  const Image& illumination = analysis.illumination.surface;
  std::vector<GBufferSample> samples(size_t(gbuffer.samples_per_pixel()));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      if (!scene.photo_clipped.empty() && scene.photo_clipped[i]) continue;
      const std::optional<uint32_t> object = matte_object_seen_whole(scene, gbuffer, x, y, samples);
      if (!object) continue;
      const Vec3& e = illumination.pixels[i];
      if (e.minCoeff() <= 1e-4f * std::max(e.maxCoeff(), 1e-12f) || e.maxCoeff() <= 0.0f) continue;
      v.object[i] = int32_t(*object);
      v.colour[i] = photo.pixels[i].cwiseQuotient(e);
    }
  return v;
}

// Per object: the differences of `value` between pixels kSteps apart along
// rows and columns, both showing the object.
std::vector<std::vector<float>> differences(const ViewPixels& view, const std::vector<float>& value, int w, int h,
                                            size_t objects) {
  std::vector<std::vector<float>> d(objects);
  for (const int step : kSteps)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * w + x;
        const int32_t o = view.object[i];
        if (o < 0) continue;
        if (x + step < w && view.object[i + step] == o) d[o].push_back(value[i + step] - value[i]);
        if (y + step < h && view.object[i + size_t(step) * w] == o)
          d[o].push_back(value[i + size_t(step) * w] - value[i]);
      }
  return d;
}

// An object's pixels for a broad sheen's fit, on a grid over the view (each
// pixel of it up to half a megapixel): the pixels, and the pairs a broad step
// apart both on the object, with the jackknife block of the first.
struct BroadPairs {
  std::vector<uint32_t> pixels;
  std::vector<uint32_t> first, second, block;
};

std::vector<BroadPairs> broad_pairs(const ViewPixels& view, int w, int h, size_t objects) {
  std::vector<BroadPairs> pairs(objects);
  const int stride = std::max(1, int(std::lround(std::sqrt(double(w) * h / kBroadPixels))));
  for (int y = 0; y < h; y += stride)
    for (int x = 0; x < w; x += stride) {
      const size_t i = size_t(y) * w + x;
      const int32_t o = view.object[i];
      if (o < 0) continue;
      BroadPairs& p = pairs[size_t(o)];
      p.pixels.push_back(uint32_t(i));
      const uint32_t b = jackknife_block(x, y, w);
      for (const int parts : kBroadStepsPerWidth) {
        const int step = std::max(1, w / parts);
        for (const size_t j : {x + step < w ? i + step : i, y + step < h ? i + size_t(step) * w : i})
          if (j != i && view.object[j] == o)
            p.first.push_back(uint32_t(i)), p.second.push_back(uint32_t(j)), p.block.push_back(b);
      }
    }
  return pairs;
}

// Two unit vectors across the plane of colours at right angles to `c`: the
// part of a change in shading that scaling c (the light's own errors, or a
// texture's light and dark) cannot make.
std::array<Vec3, 2> across_colour(const Vec3& c) {
  const Vec3 n = c.normalized();
  int least = 0;
  n.cwiseAbs().minCoeff(&least);
  const Vec3 u = n.cross(Vec3::Unit(least)).normalized();
  return {u, n.cross(u)};
}

// The shading colour of `objects`: their pixels' median in each channel.
Vec3 median_colour(const ViewPixels& view, const std::vector<BroadPairs>& pairs, const std::vector<uint32_t>& objects) {
  Vec3 c;
  for (int channel = 0; channel < 3; ++channel) {
    std::vector<float> v;
    for (const uint32_t o : objects)
      for (const uint32_t i : pairs[o].pixels) v.push_back(view.colour[i][channel]);
    c[channel] = median_of(std::move(v));
  }
  return c;
}

// A broad sheen's fit for one unit at one roughness: the changes over its
// pairs of the shading and of the predicted highlight / illumination
// (`predicted`), each in the two colours across `colour`.
struct BroadFit {
  HighlightFit fit;
  std::vector<float> dx, dy;    // the changes it was fitted to
  std::vector<uint32_t> block;  // each one's block of the view
};
BroadFit fit_broad_sheen(const std::vector<const BroadPairs*>& pairs, const ViewPixels& view,
                         const std::vector<Vec3>& predicted, const Vec3& colour) {
  const std::array<Vec3, 2> across = across_colour(colour);
  BroadFit f;
  for (const BroadPairs* p : pairs)
    for (size_t k = 0; k < p->first.size(); ++k) {
      const Vec3 x = predicted[p->second[k]] - predicted[p->first[k]];
      const Vec3 y = view.colour[p->second[k]] - view.colour[p->first[k]];
      for (const Vec3& u : across) f.dx.push_back(x.dot(u)), f.dy.push_back(y.dot(u)), f.block.push_back(p->block[k]);
    }
  f.fit = fit_highlight(f.dx, f.dy, 1.0f / kDefaultSpecular);
  return f;
}

// The objects named `glossy`, each at `roughness` and the default specular.
std::map<std::string, Gloss> all_at(const std::vector<std::string>& glossy, float roughness) {
  std::map<std::string, Gloss> materials;
  for (const std::string& name : glossy) materials[name] = Gloss{roughness, kDefaultSpecular};
  return materials;
}

// The highlights every object in `glossy` would show at `roughness`, at the
// default specular: of the scene's lights and environment. The surfaces the
// gloss mirrors are left out: predicted from the photo, their pattern
// follows the bounce light and with it the illumination's own errors, which
// then pass for a highlight (docs/benchmarks.md, "Materials from the photo").
Image predicted_highlights(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const Lighting& lighting,
                           const std::vector<std::string>& glossy, float roughness,
                           const MaterialEstimationOptions& options, Progress& progress) {
  const SurfaceGloss gloss(all_at(glossy, roughness), scene.mesh);
  const Integrator integrator(rays, lighting, nullptr);
  const ReflectedRadiance nothing_mirrored = [](const SurfacePoint&, Rng&) -> Vec3 { return Vec3::Zero(); };
  const SpecularReflection specular(integrator, gloss, nothing_mirrored);
  return render_specular(gbuffer, scene.camera, specular, options.paths_per_pixel, options.seed, progress,
                         fmt::format("highlights at roughness {:.2f}", roughness));
}

// What the tests of a broad sheen share: the scene as analysed, the photo
// as divided and its view, the lighting of the highlights, and the radiance
// the photo and probes show (where the analysis's bounces take it: the
// surfaces a sheen mirrors).
struct SheenInputs {
  const Scene& scene;
  const RayScene& rays;
  const GBuffer& gbuffer;
  const Analysis& analysis;
  const Lighting& lighting;
  const Image& photo;
  const ViewPixels& view;
  const std::vector<EstimationUnit>& units;
  const PhotoRadiance* shown;
  const MaterialEstimationOptions& options;
  Progress& progress;
};

// `fit` (at `roughness`) kept as the best where it explains more than the
// best so far. A sheen is fainter than a dielectric's brightest: a fit held
// at that bound is something else's shape (a checker's colours).
void keep_if_better(BroadFit&& fit, float roughness, BroadFit& best, float& best_roughness) {
  const bool within = fit.fit.scale > 0.0f && fit.fit.scale < 1.0f / kDefaultSpecular;
  if (within && fit.fit.explained > best.fit.explained) best = std::move(fit), best_roughness = roughness;
}

// The units of `estimates` left matte that are coloured, tried for a broad
// sheen: the highlights their gloss would show as the photo was taken (the
// surfaces it mirrors as the photo shows them) at each roughness, the one
// whose changes over broad steps, across the unit's colour, explain most
// of its shading's, kept where its strength stands clear of none.
void find_broad_sheens(const SheenInputs& in, std::vector<MaterialEstimate>& estimates) {
  const int w = in.gbuffer.width(), h = in.gbuffer.height();
  const std::vector<BroadPairs> pairs = broad_pairs(in.view, w, h, in.scene.mesh.objects.size());
  std::vector<size_t> tried;
  std::vector<Vec3> colour;
  std::vector<std::string> candidates;
  for (size_t k = 0; k < in.units.size(); ++k) {
    MaterialEstimate& m = estimates[k];
    if (m.gloss) continue;
    const Vec3 c = median_colour(in.view, pairs, in.units[k].objects);
    if (c.maxCoeff() <= 0.0f || 1.0f - c.minCoeff() / c.maxCoeff() < kMinChroma) {
      m.reason += "; grey, so a broad sheen would not be told from its light";
      continue;
    }
    std::set<uint32_t> blocks;
    for (const uint32_t o : in.units[k].objects) blocks.insert(pairs[o].block.begin(), pairs[o].block.end());
    if (blocks.size() < kMinBlocks) {
      m.reason += "; too small a part of the view to tell a broad sheen on";
      continue;
    }
    tried.push_back(k), colour.push_back(c);
    candidates.insert(candidates.end(), m.objects.begin(), m.objects.end());
  }
  if (tried.empty()) return;
  AnalysisOptions render = in.analysis.options;
  render.paths_per_pixel = in.options.paths_per_pixel, render.seed = in.options.seed;
  std::vector<BroadFit> best(tried.size());
  std::vector<float> best_roughness(tried.size(), 0.0f);
  std::vector<Vec3> predicted(size_t(w) * h, Vec3::Zero());
  for (const float roughness : kRoughnessGrid) {
    const Image highlights = photo_highlights(
        in.scene, in.rays, in.gbuffer, in.lighting, SurfaceGloss(all_at(candidates, roughness), in.scene.mesh),
        in.shown, render, in.progress, fmt::format("sheens at roughness {:.2f}", roughness));
    for (size_t i = 0; i < predicted.size(); ++i)
      if (in.view.object[i] >= 0)
        predicted[i] = highlights.pixels[i].cwiseQuotient(in.analysis.illumination.surface.pixels[i]);
    for (size_t t = 0; t < tried.size(); ++t) {
      std::vector<const BroadPairs*> unit_pairs;
      for (const uint32_t o : in.units[tried[t]].objects) unit_pairs.push_back(&pairs[o]);
      keep_if_better(fit_broad_sheen(unit_pairs, in.view, predicted, colour[t]), roughness, best[t], best_roughness[t]);
    }
  }
  for (size_t t = 0; t < tried.size(); ++t) {
    MaterialEstimate& m = estimates[tried[t]];
    const float specular = kDefaultSpecular * best[t].fit.scale;
    m.colour_significance = jackknife_significance(best[t].dx, best[t].dy, best[t].block);
    if (*m.colour_significance < kMinSignificance)
      m.reason += fmt::format("; a broad sheen stands {:.1f} standard errors clear of none ({:.1f} needed)",
                              *m.colour_significance, kMinSignificance);
    else if (specular < kMinSpecular)
      m.reason += fmt::format("; its broad sheen is faint (specular {:.3f}, under {:.2f})", specular, kMinSpecular);
    else
      m.gloss = Gloss{best_roughness[t], specular}, m.cue = GlossCue::colour, m.reason.clear();
  }
}

// A point of an object tried by two views that the photo and a probe both
// show, and how their radiances differ: (photo - probe) over their mean, in
// luminance.
struct SeenTwice {
  SurfacePoint point;
  Vec3 probe_position;
  uint32_t block;  // the photo pixel's jackknife block
  float change, mean;
};

// Per unit: its points seen twice, from each probe that shows the scene as
// the photo does (probe_exposure.h), on pixels that show the unit whole.
std::vector<std::vector<SeenTwice>> points_seen_twice(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer,
                                                      const Image& photo, const ViewPixels& view,
                                                      const std::vector<int32_t>& unit_of, size_t units) {
  const int w = gbuffer.width();
  std::vector<std::vector<SeenTwice>> seen(units);
  for (const Probe& probe : scene.probes) {
    const std::vector<SharedPoint> shared = points_shared_with_photo(probe, scene, rays, gbuffer);
    if (!photo_exposure_from(shared, scene.photo, probe.path)) continue;
    for (const SharedPoint& s : shared) {
      const uint32_t o = scene.mesh.triangle_objects[s.point.prim];
      if (unit_of[o] < 0 || view.object[s.pixel] != int32_t(o)) continue;
      const float p = luminance(photo.pixels[s.pixel]), q = luminance(s.probe), mean = 0.5f * (p + q);
      if (!(mean > 0.0f)) continue;
      const int x = int(s.pixel % size_t(w)), y = int(s.pixel / size_t(w));
      seen[size_t(unit_of[o])].push_back({s.point, probe.position, jackknife_block(x, y, w), (p - q) / mean, mean});
    }
  }
  // Every so many of an object's points where it has more than the fit
  // needs (a large probe shares hundreds of thousands).
  for (std::vector<SeenTwice>& points : seen)
    if (points.size() > kMaxPointsSeenTwice) {
      const size_t stride = (points.size() + kMaxPointsSeenTwice - 1) / kMaxPointsSeenTwice;
      for (size_t i = 0; i * stride < points.size(); ++i) points[i] = points[i * stride];
      points.resize((points.size() + stride - 1) / stride);
    }
  return seen;
}

// The change of each point's highlight from its probe's view to the
// camera's, over its mean radiance (as SeenTwice::change): `paths` of
// `specular`'s estimates each way.
std::vector<float> predicted_changes(const std::vector<SeenTwice>& points, const SpecularReflection& specular,
                                     const Vec3& camera, int paths, uint64_t seed) {
  std::vector<float> change(points.size());
  tbb::parallel_for(size_t(0), points.size(), [&](size_t n) {
    Rng rng(seed ^ 0x7477696365ull, n);
    Vec3 sum = Vec3::Zero();
    for (int i = 0; i < paths; ++i)
      sum += specular.radiance(points[n].point, camera, rng) -
             specular.radiance(points[n].point, points[n].probe_position, rng);
    change[n] = luminance(sum) / float(paths) / points[n].mean;
  });
  return change;
}

// The units of `estimates` still matte or found by their colour, tried for
// a sheen seen from two places: where a probe and the camera see the same
// points of a unit, the change of its radiance between the two views
// against that of its highlight at each broad roughness (about their
// medians: an exposure error between photo and probe changes every point
// alike), the best kept where it stands clear of none and explains enough
// of the change. It replaces a sheen found by its colour: it compares
// radiances, where the colour's test divides by the simulated light (a
// room's wall at 0.5 / 0.5: 0.55 / 0.77 by two views, 0.40 / 0.22 by its
// colour; docs/benchmarks.md, "A sheen seen twice").
void find_sheens_seen_twice(const SheenInputs& in, std::vector<MaterialEstimate>& estimates) {
  const auto open = [&](size_t k) { return !estimates[k].gloss || estimates[k].cue == GlossCue::colour; };
  std::vector<int32_t> unit_of(in.scene.mesh.objects.size(), -1);
  std::vector<std::string> candidates;
  for (size_t k = 0; k < in.units.size(); ++k)
    if (open(k)) {
      for (const uint32_t o : in.units[k].objects) unit_of[o] = int32_t(k);
      candidates.insert(candidates.end(), estimates[k].objects.begin(), estimates[k].objects.end());
    }
  if (candidates.empty()) return;
  std::vector<std::vector<SeenTwice>> seen =
      points_seen_twice(in.scene, in.rays, in.gbuffer, in.photo, in.view, unit_of, in.units.size());
  std::vector<size_t> tried;
  for (size_t k = 0; k < in.units.size(); ++k) {
    if (!open(k)) continue;
    std::set<uint32_t> blocks;
    for (const SeenTwice& p : seen[k]) blocks.insert(p.block);
    if (blocks.size() >= kMinBlocks)
      tried.push_back(k);
    else if (!in.scene.probes.empty() && !estimates[k].gloss)
      estimates[k].reason += "; too little of it seen by a probe as by the camera to compare their views";
  }
  if (tried.empty()) return;
  std::vector<BroadFit> best(in.units.size());
  std::vector<float> best_roughness(in.units.size(), 0.0f);
  for (const float roughness : kRoughnessGrid) {
    if (roughness < kMinTwoViewsRoughness) continue;
    const SurfaceGloss gloss(all_at(candidates, roughness), in.scene.mesh);
    const PhotoSpecular specular(in.rays, in.lighting, gloss, in.shown, in.analysis.options);
    in.progress.begin(fmt::format("sheens seen twice at roughness {:.2f}", roughness), int64_t(tried.size()));
    for (const size_t k : tried) {
      const std::vector<SeenTwice>& points = seen[k];
      const std::vector<float> predicted = predicted_changes(points, specular.reflection(), in.scene.camera.position(),
                                                             in.options.paths_per_pixel, in.options.seed);
      std::vector<float> shown_change(points.size());
      for (size_t n = 0; n < points.size(); ++n) shown_change[n] = points[n].change;
      const float predicted_middle = median_of(predicted), shown_middle = median_of(shown_change);
      BroadFit f;
      for (size_t n = 0; n < points.size(); ++n) {
        f.dx.push_back(predicted[n] - predicted_middle);
        f.dy.push_back(shown_change[n] - shown_middle);
        f.block.push_back(points[n].block);
      }
      f.fit = fit_highlight(f.dx, f.dy, 1.0f / kDefaultSpecular);
      keep_if_better(std::move(f), roughness, best[k], best_roughness[k]);
      in.progress.advance();
    }
    in.progress.end();
  }
  for (const size_t k : tried) {
    MaterialEstimate& m = estimates[k];
    const float specular = kDefaultSpecular * best[k].fit.scale;
    m.two_views_significance = jackknife_significance(best[k].dx, best[k].dy, best[k].block);
    const bool clear = *m.two_views_significance >= kMinSignificance && best[k].fit.explained >= kMinExplainedTwoViews;
    if (clear && specular >= kMinSpecular) {
      m.gloss = Gloss{best_roughness[k], specular};
      m.cue = GlossCue::two_views;
      m.explained = best[k].fit.explained;
      m.reason.clear();
    } else if (m.gloss) {
      continue;  // found by its colour, and kept so
    } else if (clear) {
      m.reason += fmt::format("; seen by a probe and the camera, its sheen is faint (specular {:.3f})", specular);
    } else {
      m.reason += fmt::format(
          "; seen by a probe and the camera, a sheen stands {:.1f} standard errors clear of none ({:.1f} needed) "
          "and explains {:.1f} % of how they differ ({:.0f} % needed)",
          *m.two_views_significance, kMinSignificance, 100.0f * best[k].fit.explained, 100.0f * kMinExplainedTwoViews);
    }
  }
}

// The photo as the analysis divided it: in its units (vignetting, exposure), less the
// highlights of the surfaces given glossy.
Image photo_as_divided(const Scene& scene, const Analysis& analysis) {
  Image photo = scene.photo;
  bring_to_analysis_units(photo, analysis);
  if (!analysis.specular.pixels.empty())
    for (size_t i = 0; i < photo.size(); ++i)
      photo.pixels[i] = (photo.pixels[i] - analysis.coverage[i] * analysis.specular.pixels[i]).cwiseMax(0.0f);
  return photo;
}

// "cap_1", or "Stone (a material: cap_1, cap_2 and 8 more)".
std::string estimate_name(const MaterialEstimate& m) {
  if (m.objects.size() == 1 && m.objects[0] == m.name) return m.name;
  std::string objects = m.objects.empty() ? std::string() : m.objects[0];
  for (size_t i = 1; i < m.objects.size() && i < 3; ++i)
    objects += (i + 1 == m.objects.size() ? " and " : ", ") + m.objects[i];
  if (m.objects.size() > 3) objects += fmt::format(" and {} more", m.objects.size() - 3);
  return fmt::format("{} (a material: {})", m.name, objects);
}

}  // namespace

std::string describe_estimate(const MaterialEstimate& m) {
  const std::string name = estimate_name(m);
  if (!m.gloss) return fmt::format("{:<16} matte: {} ({} pixels)", name, m.reason, m.pixels);
  const std::string found =
      fmt::format("{:<16} glossy: roughness {:.2f}, specular {:.2f}", name, m.gloss->roughness, m.gloss->specular);
  switch (m.cue) {
    case GlossCue::colour:
      return fmt::format("{} (a broad sheen, {:.1f} standard errors clear of none; {} pixels)", found,
                         m.colour_significance.value_or(0.0f), m.pixels);
    case GlossCue::two_views:
      return fmt::format(
          "{} (a sheen that differs between a probe's view and the camera's, {:.1f} standard errors clear of "
          "none; it explains {:.0f} % of how they differ; {} pixels)",
          found, m.two_views_significance.value_or(0.0f), 100.0f * m.explained, m.pixels);
    case GlossCue::highlight:
      break;
  }
  return fmt::format("{} (its highlights explain {:.0f} % of its shading's fine variation; {} pixels){}", found,
                     100.0f * m.explained, m.pixels,
                     m.gloss->specular >= 1.0f
                         ? "; as bright as a dielectric's get: a metal's, brighter and tinted, are not modelled"
                         : "");
}

std::map<std::string, Gloss> with_estimates(std::map<std::string, Gloss> given,
                                            const std::vector<MaterialEstimate>& estimates) {
  for (const MaterialEstimate& m : estimates)
    if (m.gloss) given[m.name] = *m.gloss;
  return given;
}

std::vector<EstimationUnit> estimation_units(const TriangleMesh& mesh) {
  // Each object's one material: kNoMaterial where it has none, or several.
  constexpr uint32_t kNone = TriangleMesh::kNoMaterial;
  const size_t objects = mesh.objects.size(), materials = mesh.has_materials() ? mesh.materials.size() : 0;
  std::vector<std::optional<uint32_t>> material_of(objects);
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    std::optional<uint32_t>& m = material_of[mesh.triangle_objects[t]];
    const uint32_t own = materials ? mesh.triangle_materials[t] : kNone;
    m = !m || *m == own ? own : kNone;
  }
  // A material is estimated as one where two or more objects are wholly
  // of it and no other triangle has it.
  std::vector<uint32_t> objects_of(materials, 0);
  std::vector<uint8_t> elsewhere(materials, 0);
  for (size_t o = 0; o < objects; ++o)
    if (material_of[o] && *material_of[o] < materials) ++objects_of[*material_of[o]];
  for (size_t t = 0; t < mesh.triangles.size() && materials; ++t) {
    const uint32_t m = mesh.triangle_materials[t];
    if (m < materials && material_of[mesh.triangle_objects[t]] != m) elsewhere[m] = 1;
  }
  std::vector<EstimationUnit> units;
  std::vector<int32_t> unit_of_material(materials, -1);
  for (uint32_t o = 0; o < objects; ++o) {
    const uint32_t m = material_of[o].value_or(kNone);
    if (m >= materials || objects_of[m] < 2 || elsewhere[m]) {
      units.push_back({mesh.objects[o], {o}});
      continue;
    }
    if (unit_of_material[m] < 0) {
      unit_of_material[m] = int32_t(units.size());
      units.push_back({mesh.materials[m], {}});
    }
    units[size_t(unit_of_material[m])].objects.push_back(o);
  }
  return units;
}

void require_named_objects(const Scene& scene) {
  if (!scene.mesh.has_objects())
    throw InputError(scene.path.string(), "/geometry",
                     "the geometry names no objects, so no materials can be written for it (export it with its "
                     "objects: an OBJ's `o` lines, a glTF's nodes)");
}

namespace {

// Huber's weight of each pair at the slope k.
std::vector<float> huber_weights(const std::vector<float>& dx, const std::vector<float>& dy, double k) {
  std::vector<float> e(dx.size());
  for (size_t i = 0; i < e.size(); ++i) e[i] = dy[i] - float(k) * dx[i];
  const float threshold = kHuber * std::max(robust_sigma(e), 1e-12f);
  for (float& x : e) x = std::min(1.0f, threshold / std::max(std::abs(x), 1e-30f));
  return e;
}

// The Huber-robust slope through the origin of dy against dx (iteratively
// reweighted least squares: the pairs across the object's texture, and the
// photo's noise, are the outliers of a highlight's shape); none where dx is 0.
std::optional<double> robust_slope(const std::vector<float>& dx, const std::vector<float>& dy) {
  double xx = 0.0, xy = 0.0;
  for (size_t i = 0; i < dx.size(); ++i) xx += double(dx[i]) * dx[i], xy += double(dx[i]) * dy[i];
  if (xx <= 0.0) return std::nullopt;
  double k = xy / xx;
  for (int iteration = 0; iteration < 30; ++iteration) {
    const std::vector<float> weight = huber_weights(dx, dy, k);
    double wxx = 0.0, wxy = 0.0;
    for (size_t i = 0; i < dx.size(); ++i) wxx += weight[i] * dx[i] * dx[i], wxy += weight[i] * dx[i] * dy[i];
    const double next = wxy / wxx;
    const bool settled = std::abs(next - k) <= 1e-5 * std::max(1.0, std::abs(k));
    k = next;
    if (settled) break;
  }
  return k;
}

}  // namespace

HighlightFit fit_highlight(const std::vector<float>& dx, const std::vector<float>& dy, float max_scale) {
  const std::optional<double> slope = robust_slope(dx, dy);
  if (!slope) return {};
  // A highlight a few pixels of noise predict fits any scale: none beyond
  // what the surface could reflect.
  const double k = std::clamp(*slope, 0.0, double(max_scale));
  std::vector<float> e(dx.size());
  for (size_t i = 0; i < e.size(); ++i) e[i] = dy[i] - float(k) * dx[i];
  const float threshold = kHuber * std::max(robust_sigma(dy), 1e-12f);
  const double before = huber_loss(dy, threshold);
  if (before <= 0.0) return {float(k), 0.0f};
  return {float(k), float(1.0 - huber_loss(e, threshold) / before)};
}

float jackknife_significance(const std::vector<float>& dx, const std::vector<float>& dy,
                             const std::vector<uint32_t>& block) {
  const std::optional<double> slope = robust_slope(dx, dy);
  if (!slope) return 0.0f;
  const std::set<uint32_t> blocks(block.begin(), block.end());
  if (blocks.size() < kMinBlocks) return 0.0f;
  // The slope fitted again without each block in turn.
  std::vector<double> without;
  std::vector<float> x, y;
  for (const uint32_t left_out : blocks) {
    x.clear(), y.clear();
    for (size_t i = 0; i < dx.size(); ++i)
      if (block[i] != left_out) x.push_back(dx[i]), y.push_back(dy[i]);
    if (const std::optional<double> k = robust_slope(x, y)) without.push_back(*k);
  }
  if (without.size() < kMinBlocks) return 0.0f;
  double mean = 0.0, spread = 0.0;
  for (const double k : without) mean += k;
  mean /= double(without.size());
  for (const double k : without) spread += (k - mean) * (k - mean);
  const double n = double(without.size()), error = std::sqrt((n - 1.0) / n * spread);
  return error > 0.0 ? float(*slope / error) : 0.0f;
}

std::vector<MaterialEstimate> estimate_materials(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer,
                                                 const Analysis& analysis, const MaterialEstimationOptions& options,
                                                 Progress& progress) {
  const int w = gbuffer.width(), h = gbuffer.height();
  if (!scene.mesh.has_objects()) return {};
  const size_t objects = scene.mesh.objects.size();
  const Image photo = photo_as_divided(scene, analysis);
  const ViewPixels view = view_pixels(scene, gbuffer, analysis, photo);
  std::vector<size_t> pixels(objects, 0);
  for (const int32_t o : view.object)
    if (o >= 0) ++pixels[o];
  std::vector<MaterialEstimate> estimates;
  std::vector<EstimationUnit> units;
  std::vector<std::string> candidates;
  for (EstimationUnit& unit : estimation_units(scene.mesh)) {
    MaterialEstimate m;
    m.name = unit.name;
    for (const uint32_t o : unit.objects) m.objects.push_back(scene.mesh.objects[o]), m.pixels += pixels[o];
    if (m.pixels < options.min_pixels) continue;
    candidates.insert(candidates.end(), m.objects.begin(), m.objects.end());
    estimates.push_back(std::move(m));
    units.push_back(std::move(unit));
  }
  if (candidates.empty()) return estimates;
  // Per unit: the differences of its objects, one after the other.
  const auto pooled = [&](const std::vector<std::vector<float>>& per_object) {
    std::vector<std::vector<float>> d(units.size());
    for (size_t k = 0; k < units.size(); ++k)
      for (const uint32_t o : units[k].objects) d[k].insert(d[k].end(), per_object[o].begin(), per_object[o].end());
    return d;
  };

  std::vector<float> mean_shading(view.colour.size());
  for (size_t i = 0; i < mean_shading.size(); ++i) mean_shading[i] = view.colour[i].mean();
  const std::vector<std::vector<float>> shading = pooled(differences(view, mean_shading, w, h, objects));
  const Lighting lighting = strategy_lighting(scene, rays, analysis.options.strategy);
  // Per unit: the best fit so far and its roughness.
  std::vector<HighlightFit> best(estimates.size());
  std::vector<float> best_roughness(estimates.size(), 0.0f);
  std::vector<uint8_t> any_highlight(estimates.size(), 0);
  std::vector<float> predicted(size_t(w) * h);
  for (const float roughness : kRoughnessGrid) {
    const Image highlights =
        predicted_highlights(scene, rays, gbuffer, lighting, candidates, roughness, options, progress);
    for (size_t i = 0; i < predicted.size(); ++i) {
      const Vec3& e = analysis.illumination.surface.pixels[i];
      predicted[i] = view.object[i] < 0 ? 0.0f : highlights.pixels[i].cwiseQuotient(e).mean();
    }
    const std::vector<std::vector<float>> highlight = pooled(differences(view, predicted, w, h, objects));
    for (size_t k = 0; k < units.size(); ++k) {
      const HighlightFit fit = fit_highlight(highlight[k], shading[k], 1.0f / kDefaultSpecular);
      if (std::any_of(highlight[k].begin(), highlight[k].end(), [](float d) { return d != 0.0f; }))
        any_highlight[k] = 1;
      if (fit.scale > 0.0f && fit.explained > best[k].explained) best[k] = fit, best_roughness[k] = roughness;
    }
  }
  for (size_t k = 0; k < estimates.size(); ++k) {
    MaterialEstimate& m = estimates[k];
    m.explained = best[k].explained;
    const float specular = kDefaultSpecular * best[k].scale;
    if (!any_highlight[k])
      m.reason = "no light or bright sky is mirrored towards the camera on it";
    else if (best[k].explained < kMinExplained)
      m.reason = fmt::format("a highlight explains {:.1f} % of its shading's fine variation (at least {:.0f} % needed)",
                             100.0f * best[k].explained, 100.0f * kMinExplained);
    else if (specular < kMinSpecular)
      m.reason = fmt::format("its highlights are faint (specular {:.3f}, under {:.2f})", specular, kMinSpecular);
    else
      m.gloss = Gloss{best_roughness[k], specular}, m.cue = GlossCue::highlight;
  }
  if (std::all_of(estimates.begin(), estimates.end(), [](const MaterialEstimate& m) { return bool(m.gloss); }))
    return estimates;
  std::unique_ptr<PhotoRadiance> shown;
  if (analysis.options.bounce_source == BounceSource::photo)
    shown = std::make_unique<PhotoRadiance>(scene.camera, gbuffer, photo, scene.probes, rays, scene.lights);
  const SheenInputs sheen{scene, rays, gbuffer, analysis, lighting, photo, view, units, shown.get(), options, progress};
  find_broad_sheens(sheen, estimates);
  find_sheens_seen_twice(sheen, estimates);
  return estimates;
}

}  // namespace relight
