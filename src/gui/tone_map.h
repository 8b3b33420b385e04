// From linear radiometry to what the screen shows: images through an
// exposure (in stops) and sRGB encoding, light colours as swatches and as
// FORMAT.md's "#rrggbb" (sRGB-encoded) hex strings.
#pragma once

#include <QColor>
#include <QImage>
#include <QString>
#include <optional>

#include "core/image.h"

namespace relight::gui {

// 8-bit sRGB of linear x 2^exposure_stops, clipped to [0,1] (write_png's encoding).
QImage to_qimage(const Image& linear, float exposure_stops);

// The display exposure a photo opens with: the stops that bring the 99th
// percentile of its pixels' brightest channel to 1 (so about 1 % shows as
// white, as a camera exposes), in half stops within [-10, 10]; 0 for a
// photo that is black almost everywhere.
float display_exposure_for(const Image& photo);

// A light colour for display: scaled down to a maximum of 1 if brighter, sRGB-encoded.
QColor display_colour(const Vec3& linear);

// "#rrggbb" of a linear colour (clipped to [0,1]); and back, linearised
// (nothing if the text is not "#" and six hex digits).
QString colour_hex(const Vec3& linear);
std::optional<Vec3> colour_from_hex(const QString& hex);

}  // namespace relight::gui
