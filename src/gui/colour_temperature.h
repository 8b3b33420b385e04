// Light colours as a temperature and a tint, the way lighting designers
// give them: the colour of a blackbody at so many kelvin, moved off the
// Planckian locus towards green (+) or magenta (-).
#pragma once

#include <optional>

#include "core/vec.h"

namespace relight::gui {

inline constexpr float kMinKelvin = 1000.0f, kMaxKelvin = 40000.0f;
// Tint is Duv (ANSI C78.377): the signed distance from the Planckian locus in
// CIE 1960 (u, v), + above it (green), - below it (magenta).
inline constexpr float kMaxTint = 0.05f;

// Linear RGB (sRGB primaries, as rig.json's colours) of a blackbody at
// `kelvin` with `tint`, both clamped to their ranges, scaled to a largest
// channel of 1 (a "#rrggbb" colour's range; the power stays the light's).
// Chromaticities outside sRGB (below about 1900 K) lose their negative channel.
Vec3 colour_from_temperature(float kelvin, float tint);

struct ColourTemperature {
  float kelvin;  // the locus's nearest point, kMinKelvin..kMaxKelvin
  float tint;    // the colour's Duv from it, clamped to ±kMaxTint
};
// The temperature and tint that come nearest to a linear RGB colour; nothing
// for black.
std::optional<ColourTemperature> temperature_of_colour(const Vec3& linear);

}  // namespace relight::gui
