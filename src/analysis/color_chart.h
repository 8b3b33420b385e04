// Surfaces of known albedo the photo shows (scene.json's `reference`): a
// grey card's polygon or object, or the 24 patches of an X-Rite
// ColorChecker Classic found from the chart's four corners.
#pragma once

#include <vector>

#include "render/gbuffer.h"
#include "scene/scene.h"

namespace relight {

struct ReferencePatch {
  std::vector<Vec2> polygon;  // photo pixels
  Vec3 albedo;                // linear
};

// The ColorChecker Classic seen with the outer corners of its corner
// patches at `corners` (photo pixels): dark skin's, then bluish green's,
// black's and white's (clockwise as the chart is read). Each of the 4 x 6
// patches is the middle 40 % of its cell, mapped through the chart plane's
// homography, so a patch border or a corner a few pixels off stays outside.
std::vector<ReferencePatch> colorchecker_patches(const std::vector<Vec2>& corners);

// The reference's patches: its polygon, or its chart's.
std::vector<ReferencePatch> reference_patches(const AlbedoReference& reference);

// The photo pixels that show a reference wholly (every G-buffer sample on
// modelled geometry; for an object, every sample on it), each with the
// albedo it should have and the patch it belongs to.
struct ReferencePixel {
  size_t pixel;
  Vec3 albedo;
  size_t patch;
};
struct ReferencePixels {
  std::vector<ReferencePixel> pixels;
  size_t patches = 0;  // of the reference, seen or not
};
ReferencePixels reference_pixels(const AlbedoReference& reference, const GBuffer& gbuffer, const TriangleMesh& mesh);

// Even-odd rule: whether p lies inside the polygon.
bool inside_polygon(const std::vector<Vec2>& polygon, const Vec2& p);

}  // namespace relight
