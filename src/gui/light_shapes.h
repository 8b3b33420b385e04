// The shapes the studio draws a light as, in world space, shared by the
// geometry view and the photo's overlay: a point's radius, a spot's cone, an
// area light's rectangle with its facing, a sun's direction.
#pragma once

#include <QColor>
#include <QPointF>
#include <functional>
#include <optional>
#include <vector>

#include "scene/light.h"

class QPainter;
class QWidget;

namespace relight::gui {

class LightingDocument;

using Polyline = std::vector<Vec3>;  // a closed one repeats its first point

// Light `light`'s outline drawn at `at` (its position; for a sun, where its
// arrow starts), facing the viewpoint `eye`: the circle of a point's or
// spot's radius; a spot's cone, `reach` long, to a ring of radius reach x
// tan(angle/2) with four lines from the apex; an area light's rectangle
// (±size/2 along its w and h sides) with an arrow along its normal; a sun's
// arrow, `reach` long, the way it shines.
std::vector<Polyline> light_shape(const Light& light, const Vec3& at, const Vec3& eye, float reach);

// How far a spot's cone (or an area light's aim) reaches: to the first
// surface it aims at, or half the geometry's size where it aims at nothing.
float aim_reach(const LightingDocument& document, const Light& light);

// Repaints `view` whenever `document`'s lights change: an edit, an added or
// removed light, a solo, a new rig.
void repaint_on_light_edits(LightingDocument& document, QWidget& view);

// A light's colour in both views: red the selected one, blue a shown light,
// yellow a switched-off one.
QColor light_colour(bool selected, bool enabled);

// The selected light's aim handle: a square in the selected colour at `at`.
void draw_aim_handle(QPainter& painter, const QPointF& at);
// The selected area light's turn handle: a circle in the selected colour.
void draw_turn_handle(QPainter& painter, const QPointF& at);
// Where an area light's turn handle is: the middle of its rectangle's `h`
// side that `up` points to (nothing for the other types).
std::optional<Vec3> turn_handle_point(const Light& light);
// The light turned about its normal so that `up` points along `towards`
// (from the light's position) in the rectangle's plane; as it was where
// `towards` is along the normal.
Light turned_towards(const Light& light, const Vec3& towards);

// Draws the polylines through `project` (world point to widget point, or
// nothing behind the eye), leaving out segments with an end not projected.
void draw_polylines(QPainter& painter, const std::vector<Polyline>& lines,
                    const std::function<std::optional<QPointF>(const Vec3&)>& project);

}  // namespace relight::gui
