// The geometry as the photo's camera sees it, for drawing over the photo
// ("through the camera"): where the model's silhouettes and creases fall
// against what the photo shows, so a camera match or a model a few pixels
// off is seen at a glance.
#pragma once

#include <QColor>
#include <QImage>

#include "render/gbuffer.h"

namespace relight::gui {

inline const QColor kGeometryEdgeColour(0, 230, 255);

// An image of the G-buffer's size, transparent but for the geometry's edges
// in kGeometryEdgeColour: each pixel that sees another surface
// (GBuffer::same_surface) than its right or lower neighbour, or sees
// geometry where that neighbour sees none (or none where it sees some).
QImage geometry_edges_image(const GBuffer& gbuffer);

}  // namespace relight::gui
