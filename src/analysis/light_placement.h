// Refining where the principal lights are from the shadows they cast: the
// user gives "a rough idea of the lights"; a shadow a few centimetres (or a
// sun a few degrees) off leaves a bright and a dark fringe in the albedo.
//
// The illumination of the fitted lighting splits into each light's direct
// light (which moves with the light) and the rest (background, bounce light:
// smooth, and taken as fixed while a light moves). The rest comes from the
// path tracer's own split, not as the illumination less a shadow-ray render:
// that difference held the noise of the given place's penumbrae, which
// pinned a soft light there. For a candidate placement
// the direct light is re-rendered with shadow rays, and the objective compares
// the photo's log ratio with the illumination's, per colour channel, over
// pixel pairs on one plane a gap apart: where both show the same shadow edge
// the ratios cancel. The per-pair penalty is capped (a texture edge costs the
// same wherever the shadows are). A wide gap first (a basin of attraction as
// wide as the gap, where a 1-pixel gap sees only shadows already within a
// pixel of the truth), then a narrow one; coordinate search on the lights'
// positions (point, spot, area) and directions (sun, spot, area), all the
// lights together: a light still misplaced leaves its fringes in what the
// others are judged by. The lights move only where the placement found
// matches the photo better by more than its noise (two standard errors),
// in the shadow mismatch or in the shading across whole planes.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "core/image.h"
#include "core/progress.h"
#include "render/gbuffer.h"
#include "render/ray_scene.h"
#include "scene/scene.h"

namespace relight {

struct PlacementOptions {
  int evaluations_per_dimension = 80;  // per light: 3 dimensions for a point, 2 for a sun, 5 for a spot or area
  int light_samples = 4;               // per pixel, for lights with a size (fixed samples: a smooth objective)
  // The first step of the search (it ends at 1/64 of it): how far off the
  // given placement may be.
  float position_step = 0.25f;      // m (point, spot, area)
  float direction_step_deg = 4.0f;  // sun, spot, area
};

struct PlacedLight {
  std::string name;
  Vec3 position_before, position_after;    // m
  Vec3 direction_before, direction_after;  // unit
  // The mean mismatch of all the lights together, pairs 16 pixels apart.
  double objective_before = 0.0, objective_after = 0.0;

  float moved_m() const;
  float turned_deg() const;
};

// The emission scene.lights[index] has when placed as `placed`: a light a
// probe measured delivers what the probe saw wherever it is tried (a lamp
// farther from the probe is brighter), one given by the user keeps its own.
using EmissionOfPlaced = std::function<Vec3(size_t index, const Light& placed)>;
inline Vec3 own_emission(size_t, const Light& placed) { return placed.emission(); }

// The line from a probe through where it sees a light (LightInProbe).
struct SightLine {
  Vec3 origin, direction;                // the probe's position; unit
  std::optional<Vec3> crossing;          // where a second probe's line passes nearest, if one sees it
  // How far along it the light's size, as the probe sees it, puts the light
  // (distance_from_apparent_size): the light is placed there, not searched
  // for along the line.
  std::optional<float> distance;
  Vec3 nearest_to(const Vec3& p) const;  // the point of the line nearest p, in front of the probe
  // Where a light given at p is placed on the line, or its search along it
  // starts: where its size puts it, the crossing, or the point nearest p.
  Vec3 start_for(const Vec3& p) const {
    return distance ? Vec3(origin + *distance * direction) : crossing ? nearest_to(*crossing) : nearest_to(p);
  }
};
// The line scene.lights[index] is seen along, if a probe sees it.
using SightLineOf = std::function<std::optional<SightLine>(size_t index)>;
inline std::optional<SightLine> no_sight_line(size_t) { return std::nullopt; }

// Moves (and turns) the enabled lights of `scene` to where their shadows and
// a spot's cone best match `photo` (the scene's, as the fit sees it: its
// vignetting divided out); a light seen along a sight line is
// moved along it only, from SightLine::start_for where it was given, and
// one whose distance the line knows is put there and only turned.
// `indirect`: the illumination (white surfaces) of the scene's lighting as
// it is, less the light straight from the lights: the environment and the
// bounce light, held fixed.
std::vector<PlacedLight> refine_light_placement(Scene& scene, const Image& photo, const RayScene& rays,
                                                const GBuffer& gbuffer, const Image& indirect,
                                                const EmissionOfPlaced& emission_of, const SightLineOf& sight_line_of,
                                                const PlacementOptions& options, Progress& progress);

}  // namespace relight
