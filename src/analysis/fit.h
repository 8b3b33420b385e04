// Automatic light fitting: the thesis set the lights' intensities and the
// background "by trial and error"; relight fits them.
//
// 0. Each probe is brought to the photo's units: the surfaces both show give
//    the ratio of their exposures (probe_exposure.h); within 5 % it is kept.
//    The ratio is written as the probe's `scale`.
// 1. A light that a probe sees gets the emission implied by the irradiance it
//    delivers at the probe (probe_lights.h): absolute, colour included. A
//    probe sees it only if the geometry hides no part of it from the
//    probe's position (a ray test; otherwise a warning, and the probe is
//    not used for that light).
// 2. Light transport is linear, so the illumination is a sum of one image per
//    light (at unit emission) and one for the background. The albedo
//    photo / illumination must not change across a shadow edge; for pixel
//    pairs on the same surface on either side of one, a(p) = a(q) is linear in
//    the unknown emissions: photo(p) L(q) - photo(q) L(p) = 0. Robust
//    (iteratively reweighted) least squares per colour channel gives the
//    background and the lights no probe sees. The overall scale of light and
//    albedo cannot be told apart from one photo: without a probe it is anchored
//    by keeping the first light as the user gave it, with a warning; and an
//    albedo above 1 on more than 1 % of the view is warned of.
// A round with fewer than 200 such pairs solves nothing: the unknowns keep
// the values given. Where the shadows are too soft to tell background from
// lights (no round solved, or the fit disagrees with the probes' mean
// radiance by over a factor of two), the background is the probes' mean
// radiance (without lights and geometry).
// Each round's bounce light uses the albedo recovered with the lighting
// fitted before (the first: white surfaces; then the mean of the last two
// rounds' albedos, which overshoot and undershoot in turn in a closed room).
// 3. Optionally, the lights are then moved to where their shadows fall
//    (light_placement.h) and their emission fitted once more; where they
//    moved, once more against the bounce light from where they now are.
// 4. A light whose size, where it then is, fills what a probe sees of it
//    only 1.5 times nearer or farther takes the size that fills it there
//    (the user's size was wrong, not the place), and the lights are fitted
//    twice more.
#pragma once

#include <string>
#include <vector>

#include "analysis/analyze.h"
#include "analysis/light_placement.h"

namespace relight {

struct FitOptions {
  int paths_per_pixel = 32;
  uint64_t seed = 1;
  int max_bounces = IntegratorOptions::kMaxBounces;
  int rounds = 4;
  bool refine_placement = false;
  PlacementOptions placement;
  // Leave the photo's lens vignetting in (photo_units.h); by default it is
  // divided out while the lights are fitted, as the analysis divides it out.
  bool keep_vignetting = false;
};

struct FittedLight {
  std::string name;
  Vec3 emission_before, emission_after;  // colour x power (x irradiance for a sun)
  std::string source;  // "probe", "shadows", "kept (scale anchor)" or "kept: too few shadow edges to fit from"
  // The factor its size (an area light's rectangle, a lamp's radius) was
  // scaled by: where a probe resolves it and the size given fills what the
  // probe sees only 1.5 times nearer or farther than the light is.
  float size_scale = 1.0f;
};

struct FitResult {
  Scene scene;  // the input scene with the fitted lights and background
  std::vector<FittedLight> lights;
  Vec3 background_before, background_after;
  std::string background_source = "shadows";  // or the probe mean, or kept
  size_t edge_pairs = 0;                      // pixel pairs across shadow edges used by the last round
  std::vector<PlacedLight> placement;         // with refine_placement
  // With a reference: the factor (per channel) every emission was scaled by
  // so that the reference's albedo came out as given; otherwise 1.
  Vec3 reference_scale = Vec3::Ones();
  // The share of the surfaces in view whose albedo, with the fitted
  // lighting, is above 1 (over 1 %: `relight fit` warns that the lights
  // are too weak for the photo).
  double albedo_above_one = 0.0;
};

FitResult fit_lighting(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer, const FitOptions& options,
                       Progress& progress);

// What `relight fit` prints: each light's emission before and after and
// where it came from, the background's, where each placed light moved or
// turned to, and the shadow-edge pixel pairs used (one line each).
std::vector<std::string> describe_fit(const FitResult& fit);

// Sets a light's colour and power (or irradiance) to give `emission`, keeping
// the luminance of its colour as the user chose it.
void set_emission(Light& light, const Vec3& emission);

}  // namespace relight
