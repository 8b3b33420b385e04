#include "gui/photo_view.h"

#include <QMouseEvent>
#include <QPainter>
#include <algorithm>
#include <cmath>

#include "analysis/analysed_scene.h"
#include "gui/light_shapes.h"
#include "gui/studio_scene.h"
#include "gui/lighting_document.h"
#include "gui/tone_map.h"

namespace relight::gui {

namespace {

// The sun's arrow starts this far (m) in front of the camera and is this
// long: only its direction on the picture means anything.
constexpr float kSunArrowDepth = 1.0f, kSunArrowLength = 0.3f;
constexpr double kDotRadius = 4.0;  // pixels
constexpr double kHandleRadius = 8.0;  // pixels a press may miss a handle by

}  // namespace

PhotoView::PhotoView(QWidget* parent) : QWidget(parent) {
  setFocusPolicy(Qt::NoFocus);
  setAttribute(Qt::WA_OpaquePaintEvent);
  setCursor(Qt::CrossCursor);
  setToolTip(tr("Click a light to select it; Ctrl+click, or click with the Place Light tool (P), to put the "
                "selected light in front of the surface.\nDrag the selected light's dot to move it over the "
                "surfaces, its square to aim it."));
}

void PhotoView::set_photo(std::shared_ptr<const Image> photo) {
  photo_ = std::move(photo);
  photo_image_ = photo_ ? to_qimage(*photo_, exposure_) : QImage();
  compose();
}

void PhotoView::set_relit(std::shared_ptr<const Image> relit) {
  relit_ = std::move(relit);
  relit_image_ = relit_ ? to_qimage(*relit_, exposure_) : QImage();
  compose();
}

void PhotoView::set_exposure(float stops) {
  exposure_ = stops;
  photo_image_ = photo_ ? to_qimage(*photo_, exposure_) : QImage();
  relit_image_ = relit_ ? to_qimage(*relit_, exposure_) : QImage();
  compose();
}

void PhotoView::set_split(double share) {
  split_ = std::clamp(share, 0.0, 1.0);
  compose();
}

void PhotoView::set_document(LightingDocument* document) {
  if (document_) disconnect(document_, nullptr, this, nullptr);
  document_ = document;
  selected_ = -1;
  if (document_) {
    repaint_on_light_edits(*document_, *this);
    connect(document_, &QObject::destroyed, this, [this] { set_document(nullptr); });
  }
  update();
}

void PhotoView::set_selected(int index) {
  selected_ = index;
  update();
}

void PhotoView::set_shapes_shown(bool shown) {
  shapes_shown_ = shown;
  update();
}

Vec3 PhotoView::sun_arrow_origin() const {
  const Camera& camera = document_->session().view().camera();
  const Vec3 ray = camera.ray_direction(0.12f * float(camera.width()), 0.15f * float(camera.height()));
  return camera.position() + kSunArrowDepth / ray.dot(camera.forward()) * ray;
}

std::optional<QPointF> PhotoView::shown(const Vec3& p) const {
  if (const auto q = document_->session().view().camera().project(p)) return widget_position(QPointF(q->x(), q->y()));
  return std::nullopt;
}

void PhotoView::draw_light_shapes(QPainter& painter) const {
  const Camera& camera = document_->session().view().camera();
  const auto project = [this](const Vec3& p) { return shown(p); };
  painter.setRenderHint(QPainter::Antialiasing);
  for (int i = 0; i < document_->light_count(); ++i) {
    const Light& light = document_->light(i);
    const bool sun = light.type == LightType::directional;
    const Vec3 at = sun ? sun_arrow_origin() : light.position;
    const auto p = project(at);
    if (!p) continue;  // behind the camera
    const QColor colour = light_colour(i == selected_, document_->shown_light(i).enabled);
    painter.setPen(QPen(colour, i == selected_ ? 2.5 : 1.8));
    painter.setBrush(Qt::NoBrush);
    draw_polylines(painter,
                   light_shape(light, at, camera.position(),
                               sun ? kSunArrowLength : aim_reach(*document_, light)),
                   project);
    painter.setPen(QPen(QColor(20, 20, 20), 1.0));
    painter.setBrush(colour);
    painter.drawEllipse(*p, kDotRadius, kDotRadius);
  }
  if (const auto aim = aim_handle()) draw_aim_handle(painter, *aim);
  if (const auto turn = turn_handle()) draw_turn_handle(painter, *turn);
}

std::optional<QPointF> PhotoView::position_handle() const {
  if (!document_ || selected_ < 0 || selected_ >= document_->light_count()) return std::nullopt;
  const Light& light = document_->light(selected_);
  if (light.type == LightType::directional) return std::nullopt;  // a sun has no position
  return shown(light.position);
}

std::optional<QPointF> PhotoView::aim_handle() const {
  if (!position_handle()) return std::nullopt;
  const Light& light = document_->light(selected_);
  if (light.type != LightType::spot && light.type != LightType::area) return std::nullopt;
  return shown(light.position + aim_reach(*document_, light) * light.direction.normalized());
}

std::optional<QPointF> PhotoView::turn_handle() const {
  if (!position_handle()) return std::nullopt;
  const auto at = turn_handle_point(document_->light(selected_));
  return at ? shown(*at) : std::nullopt;
}

PhotoView::Handle PhotoView::handle_at(const QPointF& widget_point) const {
  const auto near = [&](const std::optional<QPointF>& handle) {
    return handle && std::hypot(handle->x() - widget_point.x(), handle->y() - widget_point.y()) <= kHandleRadius;
  };
  if (!shapes_shown_) return Handle::none;
  if (near(aim_handle())) return Handle::aim;
  if (near(turn_handle())) return Handle::turn;
  return near(position_handle()) ? Handle::position : Handle::none;
}

Vec3 PhotoView::world_up() const { return document_->scene().camera.spec().up.normalized(); }

std::optional<Vec3> PhotoView::surface_at(const QPointF& widget_point) const {
  const auto pixel = image_position(widget_point);
  if (!pixel) return std::nullopt;
  const Camera& camera = document_->session().view().camera();
  SurfacePoint hit;
  if (!document_->studio_scene().analysed->rays().intersect(
          camera.position(), camera.ray_direction(float(pixel->x()), float(pixel->y())), hit))
    return std::nullopt;
  return hit.position;
}

void PhotoView::compose() {
  displayed_ = relit_image_;
  shown_ = QImage();
  if (!displayed_.isNull() && !photo_image_.isNull() && split_ > 0.0) {
    const QImage before = photo_image_.size() == displayed_.size()
                              ? photo_image_
                              : photo_image_.scaled(displayed_.size(), Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
    const int columns = int(std::lround(split_ * displayed_.width()));
    QPainter painter(&displayed_);
    painter.drawImage(QRect(0, 0, columns, displayed_.height()), before, QRect(0, 0, columns, before.height()));
  }
  update();
}

QRectF PhotoView::picture_rect() const {
  if (displayed_.isNull()) return {};
  QSizeF fitted = QSizeF(displayed_.size()).scaled(QSizeF(size()), Qt::KeepAspectRatio);
  return QRectF(QPointF(0.5 * (width() - fitted.width()), 0.5 * (height() - fitted.height())), fitted);
}

std::optional<QPointF> PhotoView::image_position(const QPointF& widget_point) const {
  const QRectF r = picture_rect();
  if (r.isEmpty() || !r.contains(widget_point)) return std::nullopt;
  return QPointF((widget_point.x() - r.left()) * displayed_.width() / r.width(),
                 (widget_point.y() - r.top()) * displayed_.height() / r.height());
}

QPointF PhotoView::widget_position(const QPointF& image_position) const {
  const QRectF r = picture_rect();
  if (r.isEmpty()) return {};
  return QPointF(r.left() + image_position.x() * r.width() / displayed_.width(),
                 r.top() + image_position.y() * r.height() / displayed_.height());
}

void PhotoView::paintEvent(QPaintEvent*) {
  QPainter painter(this);
  painter.fillRect(rect(), QColor(28, 28, 30));
  if (displayed_.isNull()) {
    painter.setPen(QColor(170, 170, 170));
    painter.drawText(rect(), Qt::AlignCenter, tr("The re-lit photo appears here"));
    return;
  }
  const QRectF r = picture_rect();
  // Scaled once per frame and size, not on every paint: the lights' shapes
  // repaint the view at each step of a drag, beside the session's render.
  if (shown_.size() != r.size().toSize())
    shown_ = displayed_.scaled(r.size().toSize(), Qt::IgnoreAspectRatio, Qt::SmoothTransformation);
  painter.drawImage(r.topLeft().toPoint(), shown_);
  if (split_ > 0.0) {
    const double x = r.left() + split_ * r.width();
    painter.setPen(QPen(QColor(255, 255, 255, 220), 1.5));
    painter.drawLine(QPointF(x, r.top()), QPointF(x, r.bottom()));
    painter.setRenderHint(QPainter::Antialiasing);
    const QFontMetrics metrics(font());
    const auto tag = [&](const QString& text, double left) {
      const QRectF box(left, r.top() + 8, metrics.horizontalAdvance(text) + 12, metrics.height() + 4);
      painter.setPen(Qt::NoPen);
      painter.setBrush(QColor(0, 0, 0, 150));
      painter.drawRoundedRect(box, 4, 4);
      painter.setPen(Qt::white);
      painter.drawText(box, Qt::AlignCenter, text);
    };
    if (x - r.left() > 70) tag(tr("Before"), x - metrics.horizontalAdvance(tr("Before")) - 20);
    if (r.right() - x > 70) tag(tr("After"), x + 8);
  }
  if (geometry_shown_ && !geometry_edges_.isNull()) {
    painter.setRenderHint(QPainter::SmoothPixmapTransform, false);  // one-pixel lines stay crisp
    painter.drawImage(r, geometry_edges_);
  }
  if (document_ && shapes_shown_) draw_light_shapes(painter);
}

void PhotoView::set_geometry_edges(QImage edges) {
  geometry_edges_ = std::move(edges);
  update();
}

void PhotoView::set_geometry_shown(bool shown) {
  geometry_shown_ = shown;
  update();
}

void PhotoView::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton) return;
  drag_ = handle_at(event->position());
  dragged_ = false;
  if (drag_ != Handle::none) {
    drag_light_ = document_->light(selected_);
    // Nothing below (a lamp over the edge of the geometry): it keeps its
    // height above what is under the cursor.
    SurfacePoint below;
    const auto under = surface_at(event->position());
    drag_height_ = document_->studio_scene().analysed->rays().intersect(drag_light_.position, -world_up(), below)
                       ? below.distance
                       : under ? (drag_light_.position - *under).dot(world_up()) : 0.0f;
    return;
  }
  if (const auto p = image_position(event->position())) emit photoClicked(*p, event->modifiers());
}

void PhotoView::mouseMoveEvent(QMouseEvent* event) {
  if (drag_ == Handle::none || !document_) return;
  if (drag_ == Handle::turn) {
    const auto pixel = image_position(event->position());
    if (!pixel) return;
    const Camera& camera = document_->session().view().camera();
    const Vec3 ray = camera.ray_direction(float(pixel->x()), float(pixel->y()));
    const Light& light = document_->light(selected_);
    const Vec3 normal = light.direction.normalized();
    const float along = ray.dot(normal);
    if (std::abs(along) < 1e-4f) return;  // the ray runs along the rectangle's plane
    const float t = (light.position - camera.position()).dot(normal) / along;
    if (t <= 0.0f) return;
    dragged_ = true;
    emit lightDragged(selected_, turned_towards(light, camera.position() + t * ray - light.position));
    return;
  }
  const auto surface = surface_at(event->position());
  if (!surface) return;
  Light moved = document_->light(selected_);
  if (drag_ == Handle::position) {
    moved.position = *surface + drag_height_ * world_up();
  } else if (const Vec3 aim = *surface - moved.position; aim.norm() > 0.0f) {
    moved.direction = aim.normalized();
  }
  dragged_ = true;
  emit lightDragged(selected_, moved);
}

void PhotoView::mouseReleaseEvent(QMouseEvent*) {
  if (drag_ != Handle::none && dragged_) emit lightDropped(selected_, drag_light_, document_->light(selected_));
  drag_ = Handle::none;
}

}  // namespace relight::gui
