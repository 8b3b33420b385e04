// Materials estimated from the photo: which of the geometry's objects shine,
// with what roughness and specular (scene.json's `materials`), found where
// the highlights of the scene's lights and environment would fall on them
// (docs/algorithms.md section 13, "Materials from the photo").
//
// For each object the photo shows, the highlights are predicted at a grid
// of roughnesses and the one whose shape best explains the fine variation
// of photo / illumination across the object (its gradients over 1, 2 and 4
// pixels, a robust fit) is kept, scaled to the photo up to the most a
// dielectric reflects (specular 1: a metal's or a tinted coat's highlights
// are not modelled). A coloured object none explains is tried for a broad
// sheen: its untinted change over a tenth of the view, in the colours its
// albedo does not have (the light's own errors scale the albedo's colour).
// An object still matte, or found by its colour, that a probe sees too is
// tried by the two views (and where they find a sheen, theirs is kept): a
// matte point sends the probe and the camera the same radiance, a shining
// one differs by the change of its highlight between them.
// It refuses to guess — the object stays matte — where no predicted
// highlight explains at least kMinExplained of the fine variation and no
// sheen stands kMinSignificance standard errors clear of none.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analysis/analyze.h"
#include "core/progress.h"
#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

// The share of an object's fine variation (the robust loss of its photo /
// illumination gradients) a highlight must explain for the object to be
// called glossy: texture, noise and the illumination's own errors explain
// none of a highlight's shape, so a matte object's best highlight explains
// well under 1 % (docs/benchmarks.md, "Materials from the photo").
inline constexpr float kMinExplained = 0.1f;

// A broad sheen is looked for on objects whose shading (photo /
// illumination) is at least this coloured (1 - its least channel over its
// greatest): on a grey one it has the colour of the light and cannot be
// told from the light's own errors.
inline constexpr float kMinChroma = 0.3f;

// How many standard errors (a jackknife over blocks of the view, a tenth of
// its width across) a broad sheen's strength must stand clear of none, and
// the fewest blocks the object must reach into for that error to be told:
// matte objects measured over ten blocks or more stand at most 3.6 (one at
// 5.1, its sheen too faint to keep), over four up to 10; broad sheens found
// 5.6 to 17 (docs/benchmarks.md, "Materials from the photo").
inline constexpr float kMinSignificance = 4.5f;
inline constexpr size_t kMinBlocks = 10;

// A sheen told by two views (a probe's and the camera's) is of a lobe this
// rough or rougher: a sharper one's highlight has a fine shape, and an
// object left matte by that shows none. It must explain at least this share
// of how the views differ, and stand kMinSignificance clear of none: matte
// objects that stand two standard errors or more explain at most 1.3 %,
// sheens found 10 to 64 % (docs/benchmarks.md, "A sheen seen twice").
inline constexpr float kMinTwoViewsRoughness = 0.2f;
inline constexpr float kMinExplainedTwoViews = 0.03f;

// The roughnesses tried (Principled's, alpha = roughness squared).
inline constexpr float kRoughnessGrid[] = {0.05f, 0.1f, 0.15f, 0.2f, 0.3f, 0.4f, 0.55f, 0.7f};

// What found a surface glossy: its highlights' fine shape, a broad sheen's
// untinted change across the view, or the change of its radiance between a
// probe's view and the camera's.
enum class GlossCue { highlight, colour, two_views };

// One estimate: of an object, or of a material several objects share whole
// (their pixels taken together; `materials` then names the material).
struct MaterialEstimate {
  std::string name;                  // the object's or the material's
  std::vector<std::string> objects;  // the objects it covers
  size_t pixels = 0;           // the pixels that show it whole
  std::optional<Gloss> gloss;  // found (by `cue`); none: left matte (`reason` says why)
  GlossCue cue = GlossCue::highlight;
  // The share the best highlight explains of its shading's fine variation,
  // or, found by two views, of how they differ.
  float explained = 0.0f;
  // Where tried for a broad sheen by its colour, or by two views: its best
  // strength over its standard error.
  std::optional<float> colour_significance, two_views_significance;
  std::string reason;
};

// Materials are the objects', whatever the photo's size: they are estimated
// from the photo reduced to at most this many pixels (reduce_photo), where
// the highlights' renders cost a fraction of a camera-sized photo's.
inline constexpr int64_t kEstimationPixels = kPreviewPixels;

struct MaterialEstimationOptions {
  int paths_per_pixel = 64;
  uint64_t seed = 1;
  // Objects shown whole by fewer pixels are left as they are.
  size_t min_pixels = 100;
};

// Throws InputError where the geometry names no objects (materials are
// written by name): before the analysis the estimate needs.
void require_named_objects(const Scene& scene);

// Estimates the objects of `scene` that `scene.materials` leaves matte, from
// the photo and `analysis` (the scene analysed with them matte, through the
// camera `gbuffer` was made with). One estimate per object the photo shows
// by at least min_pixels whole pixels, in the geometry's order; objects
// made of one material that no other surface has (ten column caps of one
// stone) are estimated together, as one.
std::vector<MaterialEstimate> estimate_materials(const Scene& scene, const RayScene& rays, const GBuffer& gbuffer,
                                                 const Analysis& analysis, const MaterialEstimationOptions& options,
                                                 Progress& progress);

// One line on an estimate, as `relight materials` prints it: "ball glossy:
// roughness 0.20, specular 0.47 (...)" or "floor matte: REASON (...)".
std::string describe_estimate(const MaterialEstimate& m);

// `given` (a scene's `materials`) with the estimates found glossy added
// under their names.
std::map<std::string, Gloss> with_estimates(std::map<std::string, Gloss> given,
                                            const std::vector<MaterialEstimate>& estimates);

// What is estimated as one: each object, but the objects made wholly of a
// material that two or more objects and no other triangle have, taken
// together under the material's name; in the order of their first object.
struct EstimationUnit {
  std::string name;
  std::vector<uint32_t> objects;
};
std::vector<EstimationUnit> estimation_units(const TriangleMesh& mesh);

// How far `dy` follows k x `dx` (one pair of pixels per entry): the robust
// (Huber) slope through the origin, held to [0, max_scale], and the share
// of dy's robust loss it explains (0: none; 1: all). Exposed for the tests.
struct HighlightFit {
  float scale = 0.0f;
  float explained = 0.0f;
};
HighlightFit fit_highlight(const std::vector<float>& dx, const std::vector<float>& dy, float max_scale);

// How many standard errors fit_highlight's slope (before it is held to a
// range) stands from 0: the delete-one-block jackknife of the slope, fitted
// again without each block in turn (`block`: each pair's block of the view,
// so that pairs near each other, whose errors go together, leave together).
// 0 where fewer than kMinBlocks blocks hold pairs. Exposed for the tests.
float jackknife_significance(const std::vector<float>& dx, const std::vector<float>& dy,
                             const std::vector<uint32_t>& block);

}  // namespace relight
