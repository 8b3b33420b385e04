#include "gui/light_shapes.h"

#include <QPainter>
#include <QWidget>
#include <cmath>

#include "analysis/analysed_scene.h"
#include "gui/lighting_document.h"
#include "gui/studio_scene.h"

namespace relight::gui {

namespace {

constexpr int kCircleSegments = 32;

// Unit vectors perpendicular to `axis` and to each other; `a` as near to
// `toward` as can be (any where `toward` is along the axis).
void perpendiculars(const Vec3& axis, const Vec3& toward, Vec3& a, Vec3& b) {
  const Vec3 off = toward - toward.dot(axis) * axis;
  if (off.norm() > 1e-6f * std::max(toward.norm(), 1e-6f)) {
    a = off.normalized();
    b = axis.cross(a);
  } else {
    orthonormal_basis(axis, a, b);
  }
}

Polyline circle(const Vec3& centre, const Vec3& a, const Vec3& b, float radius) {
  Polyline line;
  for (int i = 0; i <= kCircleSegments; ++i) {
    const float t = 2.0f * kPi * float(i) / float(kCircleSegments);
    line.push_back(centre + radius * (std::cos(t) * a + std::sin(t) * b));
  }
  return line;
}

// An arrow from `from` along unit `dir`, `length` long, its head in the
// plane facing `eye`.
void add_arrow(std::vector<Polyline>& lines, const Vec3& from, const Vec3& dir, float length, const Vec3& eye) {
  const Vec3 tip = from + length * dir;
  Vec3 side, unused;
  perpendiculars(dir, (eye - tip).cross(dir), side, unused);
  const Vec3 back = tip - 0.2f * length * dir;
  lines.push_back({from, tip});
  lines.push_back({back + 0.1f * length * side, tip, back - 0.1f * length * side});
}

}  // namespace

std::vector<Polyline> light_shape(const Light& light, const Vec3& at, const Vec3& eye, float reach) {
  std::vector<Polyline> lines;
  const Vec3 dir = light.direction.normalized();
  if ((light.type == LightType::point || light.type == LightType::spot) && light.radius > 0.0f) {
    Vec3 a, b;
    orthonormal_basis((eye - at).normalized(), a, b);  // the sphere's outline, facing the eye
    lines.push_back(circle(at, a, b, light.radius));
  }
  if (light.type == LightType::spot) {
    Vec3 a, b;
    perpendiculars(dir, eye - at, a, b);
    const Vec3 centre = at + reach * dir;
    const float ring = reach * std::tan(0.5f * radians(light.spot_angle_deg));
    lines.push_back(circle(centre, a, b, ring));
    for (const Vec3& side : {a, b, Vec3(-a), Vec3(-b)}) lines.push_back({at, centre + ring * side});
  } else if (light.type == LightType::area) {
    // The axes of LightSampler: w across `up`, h along it.
    const Vec3 w = dir.cross(light.up).normalized(), h = w.cross(dir);
    const Vec3 hw = 0.5f * light.size.x() * w, hh = 0.5f * light.size.y() * h;
    lines.push_back({at - hw - hh, at + hw - hh, at + hw + hh, at - hw + hh, at - hw - hh});
    add_arrow(lines, at, dir, 0.5f * std::max(light.size.x(), light.size.y()), eye);
  } else if (light.type == LightType::directional) {
    add_arrow(lines, at, dir, reach, eye);
  }
  return lines;
}

float aim_reach(const LightingDocument& document, const Light& light) {
  const float fallback = 0.5f * document.scene().mesh.bounds().diagonal().norm();
  SurfacePoint hit;
  if (document.studio_scene().analysed->rays().intersect(light.position, light.direction.normalized(), hit, fallback))
    return hit.distance;
  return fallback;
}

void repaint_on_light_edits(LightingDocument& document, QWidget& view) {
  QObject::connect(&document, &LightingDocument::lightChanged, &view, qOverload<>(&QWidget::update));
  QObject::connect(&document, &LightingDocument::lightInserted, &view, qOverload<>(&QWidget::update));
  QObject::connect(&document, &LightingDocument::lightRemoved, &view, qOverload<>(&QWidget::update));
  QObject::connect(&document, &LightingDocument::soloChanged, &view, qOverload<>(&QWidget::update));
  QObject::connect(&document, &LightingDocument::rigReset, &view, qOverload<>(&QWidget::update));
}

QColor light_colour(bool selected, bool enabled) {
  if (selected) return QColor(220, 40, 40);
  return enabled ? QColor(40, 110, 230) : QColor(240, 200, 30);
}

void draw_aim_handle(QPainter& painter, const QPointF& at) {
  constexpr double kHalf = 5.0;  // pixels
  painter.setPen(QPen(light_colour(true, true), 2.0));
  painter.setBrush(Qt::NoBrush);
  painter.drawRect(QRectF(at - QPointF(kHalf, kHalf), QSizeF(2 * kHalf, 2 * kHalf)));
}

void draw_turn_handle(QPainter& painter, const QPointF& at) {
  painter.setPen(QPen(light_colour(true, true), 2.0));
  painter.setBrush(Qt::NoBrush);
  painter.drawEllipse(at, 5.0, 5.0);
}

std::optional<Vec3> turn_handle_point(const Light& light) {
  if (light.type != LightType::area) return std::nullopt;
  return Vec3(light.position + 0.5f * light.size.y() * area_light_sides(light).h);
}

Light turned_towards(const Light& light, const Vec3& towards) {
  const Vec3 normal = light.direction.normalized();
  const Vec3 in_plane = towards - towards.dot(normal) * normal;
  Light turned = light;
  if (in_plane.norm() > 1e-6f * std::max(1.0f, towards.norm())) turned.up = in_plane.normalized();
  return turned;
}

void draw_polylines(QPainter& painter, const std::vector<Polyline>& lines,
                    const std::function<std::optional<QPointF>(const Vec3&)>& project) {
  for (const Polyline& line : lines) {
    std::optional<QPointF> previous;
    for (const Vec3& p : line) {
      const auto q = project(p);
      if (q && previous) painter.drawLine(*previous, *q);
      previous = q;
    }
  }
}

}  // namespace relight::gui
