#include "gui/geometry_view.h"

#include <QKeyEvent>
#include <QMouseEvent>
#include <QPainter>
#include <QWheelEvent>
#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "analysis/analysed_scene.h"
#include "gui/light_shapes.h"
#include "gui/studio_scene.h"
#include "render/gbuffer.h"

namespace relight::gui {

namespace {

constexpr float kFieldOfViewDeg = 45.0f;
constexpr float kPickRadius = 10.0f;  // pixels
constexpr float kLargeStep = 10.0f;   // Shift
constexpr float kSunArrow = 0.3f;     // of the scene's size

// 1, 2 or 5 times a power of ten, the nearest at or below `x`; a negative
// power divides, so that 0.05 is the float nearest 0.05.
float nice_step(float x) {
  const int exponent = int(std::floor(std::log10(x)));
  const auto times_decade = [exponent](float m) {
    return exponent >= 0 ? m * std::pow(10.0f, float(exponent)) : m / std::pow(10.0f, float(-exponent));
  };
  for (float m : {5.0f, 2.0f})
    if (x >= times_decade(m)) return times_decade(m);
  return times_decade(1.0f);
}

Vec3 any_perpendicular(const Vec3& n) {
  Vec3 a, b;
  orthonormal_basis(n, a, b);
  return a;
}

// The pixels seen_bounds looks at, at most: every pixel of a photo up to
// 640 x 480, every n-th along both axes of a larger one. Each is a ray (the
// compact G-buffer recomputes it), on the window's thread: at every pixel of
// an 8-Mpixel photo this took 3.5 s (docs/benchmarks.md, BM_OpenLargePhoto).
constexpr double kSeenBoundsPixels = 640.0 * 480.0;

// What the photo's camera sees, per axis between the 10th and 90th
// percentile of its pixels' surfaces, with the lights that have a position
// and the camera.
Eigen::AlignedBox3f seen_bounds(const LightingDocument& document) {
  constexpr double kTail = 0.10;
  const GBuffer& g = document.studio_scene().analysed->gbuffer();
  const int stride = std::max(1, int(std::ceil(std::sqrt(double(g.width()) * double(g.height()) / kSeenBoundsPixels))));
  std::array<std::vector<float>, 3> axes;
  for (int y = 0; y < g.height(); y += stride)
    for (int x = 0; x < g.width(); x += stride)
      if (const GBufferSample s = g.central(x, y); s.hit)
        for (int a = 0; a < 3; ++a) axes[size_t(a)].push_back(s.surface.position[a]);
  Eigen::AlignedBox3f box;
  if (!axes[0].empty()) {
    Vec3 lo, hi;
    const auto percentile = [](std::vector<float>& v, double share) {
      const auto at = v.begin() + std::ptrdiff_t(share * double(v.size() - 1));
      std::nth_element(v.begin(), at, v.end());
      return *at;
    };
    for (int a = 0; a < 3; ++a) {
      lo[a] = percentile(axes[size_t(a)], kTail);
      hi[a] = percentile(axes[size_t(a)], 1.0 - kTail);
    }
    box.extend(lo), box.extend(hi);
  }
  for (int i = 0; i < document.light_count(); ++i)
    if (document.light(i).type != LightType::directional) box.extend(document.light(i).position);
  box.extend(document.scene().camera.position());
  return box;
}

// The part of a triangle at least `near` in front of the eye (clipped by
// Sutherland and Hodgman's method): a ground reaching behind the viewpoint
// is still drawn where it is in front.
std::vector<Vec3> in_front_of(const Vec3& eye, const Vec3& forward, const std::array<Vec3, 3>& triangle,
                              float near) {
  std::vector<Vec3> kept;
  for (size_t i = 0; i < 3; ++i) {
    const Vec3 &p = triangle[i], &q = triangle[(i + 1) % 3];
    const float dp = (p - eye).dot(forward) - near, dq = (q - eye).dot(forward) - near;
    if (dp >= 0.0f) kept.push_back(p);
    if ((dp >= 0.0f) != (dq >= 0.0f)) kept.push_back(p + dp / (dp - dq) * (q - p));
  }
  return kept;
}

}  // namespace

GeometryView::GeometryView(QWidget* parent) : QWidget(parent) {
  setFocusPolicy(Qt::StrongFocus);
  setMouseTracking(false);
  setAttribute(Qt::WA_OpaquePaintEvent);
  setToolTip(tr("Click a light to select it, drag it to move it; drag elsewhere to orbit, wheel to zoom.\n"
                "Arrows: up/down and sideways; Home/End: forwards/backwards; Shift: 10\u00d7 further."));
}

void GeometryView::set_document(LightingDocument* document) {
  if (document_) disconnect(document_, nullptr, this, nullptr);
  document_ = document;
  selected_ = -1;
  if (document_) {
    const Scene& scene = document_->scene();
    world_up_ = scene.camera.spec().up.normalized();
    const Vec3 forward = scene.camera.forward();
    const Vec3 horizontal = forward - forward.dot(world_up_) * world_up_;
    reference_heading_ = horizontal.norm() > 1e-4f ? Vec3(horizontal.normalized()) : any_perpendicular(world_up_);
    const Eigen::AlignedBox3f seen = seen_bounds(*document_);
    seen_centre_ = seen.isEmpty() ? scene.camera.spec().look_at : Vec3(seen.center());
    scene_size_ = seen.isEmpty() ? 1.0f : std::max(seen.diagonal().norm(), 1e-3f);
    move_step_ = nice_step(scene_size_ / 100.0f);
    repaint_on_light_edits(*document_, *this);
    connect(document_, &QObject::destroyed, this, [this] { set_document(nullptr); });
  }
  reset_orbit();
}

void GeometryView::set_selected(int index) {
  selected_ = index;
  update();
}

void GeometryView::set_orbit(float yaw_deg, float pitch_deg, float distance) {
  yaw_deg_ = yaw_deg;
  pitch_deg_ = std::clamp(pitch_deg, -89.0f, 89.0f);
  distance_ = std::max(distance, 1e-3f * scene_size_);
  geometry_changed();
}

void GeometryView::reset_orbit() {
  centre_ = seen_centre_;
  set_orbit(0.0f, 35.0f, 1.3f * scene_size_);
}

void GeometryView::frame_all() {
  if (!document_) return;
  const Eigen::AlignedBox3f bounds = document_->scene().mesh.bounds();
  if (bounds.isEmpty()) return;
  centre_ = bounds.center();
  set_orbit(yaw_deg_, pitch_deg_, 1.3f * bounds.diagonal().norm());
}

void GeometryView::frame_selected() {
  if (!document_ || selected_ < 0 || selected_ >= document_->light_count()) return;
  centre_ = marker_position(document_->light(selected_));
  set_orbit(yaw_deg_, pitch_deg_, 0.4f * scene_size_);
}

Vec3 GeometryView::heading() const {
  const float yaw = radians(yaw_deg_);
  const Vec3 side = world_up_.cross(reference_heading_);
  return (std::cos(yaw) * reference_heading_ + std::sin(yaw) * side).normalized();
}

GeometryView::MoveFrame GeometryView::move_frame() const {
  const Vec3 forward = heading();
  return {forward.cross(world_up_).normalized(), world_up_, forward};
}

std::optional<Vec3> GeometryView::key_move(int key, Qt::KeyboardModifiers modifiers) const {
  const MoveFrame f = move_frame();
  const float step = modifiers & Qt::ShiftModifier ? kLargeStep * move_step_ : move_step_;
  switch (key) {
    case Qt::Key_Up: return Vec3(step * f.up);
    case Qt::Key_Down: return Vec3(-step * f.up);
    case Qt::Key_Right: return Vec3(step * f.right);
    case Qt::Key_Left: return Vec3(-step * f.right);
    case Qt::Key_Home: return Vec3(step * f.forward);
    case Qt::Key_End: return Vec3(-step * f.forward);
    default: return std::nullopt;
  }
}

GeometryView::Eye GeometryView::eye() const {
  const float pitch = radians(pitch_deg_);
  Eye e;
  e.forward = (std::cos(pitch) * heading() - std::sin(pitch) * world_up_).normalized();
  e.position = centre_ - distance_ * e.forward;
  e.right = e.forward.cross(world_up_).normalized();
  e.up = e.right.cross(e.forward);
  e.focal = 0.5f * float(height()) / std::tan(0.5f * radians(kFieldOfViewDeg));
  return e;
}

std::optional<QPointF> GeometryView::project(const Vec3& p) const {
  const Eye e = eye();
  const Vec3 d = p - e.position;
  const float z = d.dot(e.forward);
  if (z < 1e-3f * scene_size_) return std::nullopt;
  return QPointF(0.5 * width() + e.focal * d.dot(e.right) / z, 0.5 * height() - e.focal * d.dot(e.up) / z);
}

Vec3 GeometryView::marker_position(const Light& light) const {
  if (light.type != LightType::directional) return light.position;
  return centre_ - 0.45f * scene_size_ * light.direction.normalized();
}

std::optional<Vec3> GeometryView::aim_point(const Light& light) const {
  if (light.type != LightType::spot && light.type != LightType::area) return std::nullopt;
  return Vec3(light.position + aim_reach(*document_, light) * light.direction.normalized());
}

float GeometryView::shape_reach(const Light& light) const {
  return light.type == LightType::spot ? aim_reach(*document_, light) : kSunArrow * scene_size_;
}

void GeometryView::geometry_changed() {
  mesh_image_ = QImage();
  update();
}

void GeometryView::resizeEvent(QResizeEvent*) { mesh_image_ = QImage(); }

void GeometryView::draw_mesh() {
  mesh_image_ = QImage(size(), QImage::Format_RGB32);
  mesh_image_.fill(QColor(46, 48, 52));
  if (!document_) return;
  const Scene& scene = document_->scene();
  const Eye e = eye();
  const Vec3 key = (0.4f * e.right + 0.8f * world_up_ - 0.3f * e.forward).normalized();
  struct Face {
    float depth;
    QPolygonF polygon;
    QColor colour;
  };
  std::vector<Face> faces;
  faces.reserve(scene.mesh.triangles.size());
  for (const auto& t : scene.mesh.triangles) {
    const Vec3 &a = scene.mesh.positions[t[0]], &b = scene.mesh.positions[t[1]], &c = scene.mesh.positions[t[2]];
    const Vec3 centroid = (a + b + c) / 3.0f;
    Vec3 n = (b - a).cross(c - a);
    if (n.norm() == 0.0f) continue;
    n.normalize();
    // The side the photo's camera sees is the front; surfaces showing this
    // view their back are left out, so walls do not hide the room (a cutaway).
    if (n.dot(scene.camera.position() - centroid) < 0.0f) n = -n;
    if (n.dot(e.position - centroid) <= 0.0f) continue;
    QPolygonF polygon;
    // Drawn farthest first by their farthest point: a ground's huge
    // triangles, reaching out of the view, go under what stands on them.
    float farthest = 0.0f;
    for (const Vec3& p : in_front_of(e.position, e.forward, {a, b, c}, 2e-3f * scene_size_))
      if (const auto q = project(p)) polygon << *q, farthest = std::max(farthest, (p - e.position).dot(e.forward));
    if (polygon.size() < 3) continue;
    const int shade = int(90.0f + 130.0f * std::abs(n.dot(key)));
    faces.push_back({farthest, polygon, QColor(shade, shade, int(shade * 0.97f))});
  }
  std::sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.depth > y.depth; });
  QPainter painter(&mesh_image_);
  painter.setRenderHint(QPainter::Antialiasing);
  for (const Face& f : faces) {
    painter.setPen(QPen(f.colour, 0.8));
    painter.setBrush(f.colour);
    painter.drawPolygon(f.polygon);
  }
}

void GeometryView::draw_camera(QPainter& painter, std::vector<Label>& labels) const {
  const Camera& camera = document_->scene().camera;
  const float depth = 0.06f * scene_size_;
  const float w = float(camera.width()), h = float(camera.height());
  std::vector<QPointF> corners;
  for (const Vec2& c : {Vec2(0, 0), Vec2(w, 0), Vec2(w, h), Vec2(0, h)})
    if (const auto q = project(camera.position() + depth / camera.ray_direction(c.x(), c.y()).dot(camera.forward()) *
                                                       camera.ray_direction(c.x(), c.y())))
      corners.push_back(*q);
  const auto apex = project(camera.position());
  if (!apex || corners.size() != 4) return;
  painter.setPen(QPen(QColor(235, 235, 235), 1.2));
  painter.setBrush(Qt::NoBrush);
  for (const QPointF& c : corners) painter.drawLine(*apex, c);
  painter.drawPolygon(corners.data(), 4);
  labels.push_back({*apex, tr("camera")});
}

void GeometryView::draw_lights(QPainter& painter, std::vector<Label>& labels) const {
  for (int i = 0; i < document_->light_count(); ++i) {
    const Light& light = document_->light(i);
    const Vec3 at = marker_position(light);
    const auto p = project(at);
    if (!p) continue;
    const QColor colour = light_colour(i == selected_, document_->shown_light(i).enabled);
    painter.setPen(QPen(colour, i == selected_ ? 2.0 : 1.4));
    painter.setBrush(Qt::NoBrush);
    draw_polylines(painter, light_shape(light, at, eye_position(), shape_reach(light)),
                   [this](const Vec3& q) { return project(q); });
    painter.setPen(QPen(QColor(20, 20, 20), 1.5));
    painter.setBrush(colour);
    const double r = i == selected_ ? 7.5 : 6.0;
    painter.drawEllipse(*p, r, r);
    labels.push_back({*p, QString::fromStdString(light.name)});
  }
  if (selected_ >= 0 && selected_ < document_->light_count()) {
    const Light& light = document_->light(selected_);
    if (const auto aim = aim_point(light))
      if (const auto q = project(*aim)) draw_aim_handle(painter, *q);
    if (const auto turn = turn_handle_point(light))
      if (const auto q = project(*turn)) draw_turn_handle(painter, *q);
  }
}

void GeometryView::paintEvent(QPaintEvent*) {
  if (mesh_image_.size() != size()) draw_mesh();
  QPainter painter(this);
  painter.drawImage(0, 0, mesh_image_);
  if (!document_) {
    painter.setPen(QColor(200, 200, 200));
    painter.drawText(rect(), Qt::AlignCenter, tr("Open a scene (File \u203a Open Scene\u2026)"));
    return;
  }
  painter.setRenderHint(QPainter::Antialiasing);
  std::vector<Label> labels;
  draw_camera(painter, labels);
  draw_lights(painter, labels);
  draw_labels(painter, labels);
  if (hasFocus()) {
    painter.setPen(QPen(palette().highlight().color(), 2));
    painter.setBrush(Qt::NoBrush);
    painter.drawRect(rect().adjusted(1, 1, -1, -1));
  }
}

std::vector<QRectF> place_labels(const std::vector<QPointF>& anchors, const std::vector<QSizeF>& sizes) {
  std::vector<QRectF> placed;
  for (size_t i = 0; i < anchors.size(); ++i) {
    const double w = sizes[i].width(), h = sizes[i].height();
    const QPointF sides[] = {{10, -h / 2}, {-10 - w, -h / 2}, {-w / 2, -10 - h}, {-w / 2, 10},
                             {10, -1.5 * h}, {10, 0.5 * h}, {10, -2.5 * h}, {10, 1.5 * h}};
    QRectF box(anchors[i] + sides[0], sizes[i]);
    for (const QPointF& side : sides) {
      const QRectF candidate(anchors[i] + side, sizes[i]);
      if (std::none_of(placed.begin(), placed.end(), [&](const QRectF& r) { return r.intersects(candidate); })) {
        box = candidate;
        break;
      }
    }
    placed.push_back(box);
  }
  return placed;
}

void GeometryView::draw_labels(QPainter& painter, const std::vector<Label>& labels) const {
  const QFontMetricsF metrics(font());
  std::vector<QPointF> anchors;
  std::vector<QSizeF> sizes;
  for (const Label& label : labels) {
    anchors.push_back(label.anchor);
    sizes.emplace_back(metrics.horizontalAdvance(label.text) + 8, metrics.height() + 2);
  }
  const std::vector<QRectF> boxes = place_labels(anchors, sizes);
  for (size_t i = 0; i < labels.size(); ++i) {
    painter.setPen(Qt::NoPen);
    painter.setBrush(QColor(20, 20, 24, 170));
    painter.drawRoundedRect(boxes[i], 3, 3);
    painter.setPen(QColor(240, 240, 240));
    painter.drawText(boxes[i], Qt::AlignCenter, labels[i].text);
  }
}

int GeometryView::light_at(const QPointF& point) const {
  int best = -1;
  double best_distance = kPickRadius;
  for (int i = 0; document_ && i < document_->light_count(); ++i)
    if (const auto p = project(marker_position(document_->light(i)))) {
      const double d = std::hypot(p->x() - point.x(), p->y() - point.y());
      if (d <= best_distance) best = i, best_distance = d;
    }
  return best;
}

bool GeometryView::on_handle(const QPointF& point, const std::optional<Vec3>& handle) const {
  const auto q = handle ? project(*handle) : std::nullopt;
  return q && std::hypot(q->x() - point.x(), q->y() - point.y()) <= kPickRadius;
}

Vec3 GeometryView::dragged(const Vec3& start, const QPointF& by) const {
  // Pixels to metres at the point's depth.
  const Eye e = eye();
  const float metres_per_pixel = std::max((start - e.position).dot(e.forward), 0.0f) / e.focal;
  return start + metres_per_pixel * (float(by.x()) * e.right - float(by.y()) * e.up);
}

Light GeometryView::sun_dragged_to(const Light& sun, const QPointF& point) const {
  const Eye e = eye();
  const Vec3 ray = (e.forward + float(point.x() - 0.5 * width()) / e.focal * e.right -
                    float(point.y() - 0.5 * height()) / e.focal * e.up)
                       .normalized();
  // The marker's sphere (marker_position) met by the ray through the point;
  // past its rim, the ray's point nearest the centre, out on the sphere.
  const float radius = 0.45f * scene_size_;
  const Vec3 to_centre = centre_ - e.position;
  const float along = to_centre.dot(ray), miss2 = to_centre.squaredNorm() - along * along;
  const Vec3 on_ray = e.position + (along - std::sqrt(std::max(0.0f, radius * radius - miss2))) * ray;
  const Vec3 out = on_ray - centre_;
  Light turned = sun;
  if (out.norm() > 0.0f) turned.direction = Vec3(-out.normalized());
  return turned;
}

void GeometryView::mousePressEvent(QMouseEvent* event) {
  if (event->button() != Qt::LeftButton || !document_) return;
  setFocus();
  drag_start_ = event->position();
  if (selected_ >= 0 && selected_ < document_->light_count()) {
    const Light& light = document_->light(selected_);
    for (const auto& [handle, drag] : {std::pair{aim_point(light), Drag::aim}, std::pair{turn_handle_point(light), Drag::turn}})
      if (on_handle(event->position(), handle)) {
        drag_light_ = light;
        drag_handle_ = *handle;
        drag_ = drag;
        return;
      }
  }
  const int hit = light_at(event->position());
  if (hit >= 0) {
    emit lightClicked(hit);
    drag_light_ = document_->light(hit);
    // A sun has no position: its marker turns it round the scene.
    drag_ = drag_light_.type == LightType::directional ? Drag::sun : Drag::light;
  } else {
    drag_ = Drag::orbit;
    drag_yaw_ = yaw_deg_;
    drag_pitch_ = pitch_deg_;
  }
}

void GeometryView::mouseMoveEvent(QMouseEvent* event) {
  const QPointF d = event->position() - drag_start_;
  if (drag_ == Drag::orbit) {
    set_orbit(drag_yaw_ - 0.4f * float(d.x()), drag_pitch_ + 0.4f * float(d.y()), distance_);
  } else if (drag_ == Drag::light && selected_ >= 0) {
    Light moved = drag_light_;
    moved.position = dragged(drag_light_.position, d);
    emit lightDragged(selected_, moved);
  } else if (drag_ == Drag::sun && selected_ >= 0) {
    emit lightDragged(selected_, sun_dragged_to(drag_light_, event->position()));
  } else if (drag_ == Drag::turn && selected_ >= 0) {
    emit lightDragged(selected_, turned_towards(drag_light_, dragged(drag_handle_, d) - drag_light_.position));
  } else if (drag_ == Drag::aim && selected_ >= 0) {
    const Vec3 aim = dragged(drag_handle_, d) - drag_light_.position;
    if (aim.norm() == 0.0f) return;
    Light aimed = drag_light_;
    aimed.direction = aim.normalized();
    emit lightDragged(selected_, aimed);
  }
}

void GeometryView::mouseReleaseEvent(QMouseEvent* event) {
  if ((drag_ == Drag::light || drag_ == Drag::aim || drag_ == Drag::turn || drag_ == Drag::sun) && selected_ >= 0 &&
      event->position() != drag_start_)
    emit lightDropped(selected_, drag_light_, document_->light(selected_));
  drag_ = Drag::none;
}

void GeometryView::wheelEvent(QWheelEvent* event) {
  set_orbit(yaw_deg_, pitch_deg_, distance_ * std::pow(0.9f, float(event->angleDelta().y()) / 120.0f));
}

void GeometryView::keyPressEvent(QKeyEvent* event) {
  if (event->key() == Qt::Key_Delete) {
    emit deleteRequested();
    return;
  }
  if (const auto delta = key_move(event->key(), event->modifiers())) {
    emit moveRequested(*delta);
    return;
  }
  QWidget::keyPressEvent(event);
}

}  // namespace relight::gui
