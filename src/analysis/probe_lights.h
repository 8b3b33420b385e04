// The principal lights in a light probe. A probe photographs the lamps and the
// sun too (thesis 3.6-3.7); relight finds each light's bright compact region
// near where the user placed it, measures its direction and the irradiance it
// delivers at the probe (which gives the light's absolute power), and removes
// it — replaced by the surrounding radiance — so that rendering with both the
// lights and the probe lights nothing twice.
#pragma once

#include <optional>
#include <vector>

#include "scene/light.h"
#include "scene/probe.h"

namespace relight {

struct LightInProbe {
  Vec3 direction;              // energy-weighted centre of the region, from the probe
  Vec3 irradiance;             // at the probe, facing the light, above the surroundings (W/m^2)
  Vec3 surround;               // median radiance of the ring around the region
  std::vector<size_t> pixels;  // the region (pixel indices)
  // What the light fills (sr), where the probe resolves it: its irradiance
  // over the radiance of its evenly bright middle. Nothing for a light only
  // a few pixels across, or one not evenly bright.
  std::optional<float> solid_angle;
};

// The light's region in the probe: its bright spot near its expected
// direction, as the probe shows it whatever size the light was given, plus
// a margin for the probe's blur. Nothing when the light is not visible there
// (no pixel stands out from its surroundings).
std::optional<LightInProbe> locate_light_in_probe(const Probe& probe, const Light& light);

// The middle, by solid angle, of what the light fills seen from `from`:
// what LightInProbe::direction measures of an evenly bright light. For a
// rectangle seen at a slant it is not the direction of its centre (its near
// half fills more of the view).
Vec3 seen_middle(const Light& light, const Vec3& from);

// How far from the probe along `direction` the light, with the size (and an
// area light's facing) the user gave it, fills the solid angle the probe
// measured: where the probe resolves a light, its size seen gives its
// distance as a second probe would. Nothing where the probe does not
// resolve it or the light has no size.
std::optional<float> distance_from_apparent_size(const Probe& probe, const Light& light, const LightInProbe& seen,
                                                 const Vec3& direction);

// How many times its size given the probe shows the light where it is: its
// distance from the probe over the distance at which, of the size given, it
// would fill what the probe sees (distance_from_apparent_size along the line
// to its centre; a rectangle or sphere scaled about the probe fills what it
// did, so this is exactly the factor its size is off). Nothing where the
// probe does not resolve it.
std::optional<float> size_seen_over_given(const Probe& probe, const Light& light, const LightInProbe& seen);

// Whether two sizes or distances in `ratio` agree: within a factor of 1.5,
// what a place given roughly explains. Further off, a light's size or its
// place is wrong.
bool sizes_agree(float ratio);

// The probe with every enabled light's region replaced by its surroundings.
Probe remove_lights_from_probe(const Probe& probe, const std::vector<Light>& lights);

// The light's emission (colour x power, or x irradiance for the sun) that
// explains the irradiance measured at the probe; nothing for a light the probe
// does not see or cannot measure (a spot facing away).
std::optional<Vec3> emission_from_probe(const Probe& probe, const Light& light, const LightInProbe& seen);

// The point nearest to two rays (a light seen from two probes); nothing when
// they are parallel.
std::optional<Vec3> triangulate(const Vec3& origin_a, const Vec3& dir_a, const Vec3& origin_b, const Vec3& dir_b);

}  // namespace relight
