// GeometryView (thesis 6.2.1): the scene's mesh seen from an orbiting
// viewpoint, with the photo's camera and every light drawn as a dot — red
// the selected one, blue a shown light, yellow a switched-off one — and its
// shape (light_shapes.h). Drawn
// with QPainter (flat-shaded triangles, back to front), so it needs no
// OpenGL. Mouse: click a dot to select it, drag it to move the light in the
// plane facing the view (a sun's: round the scene, turning where it shines
// from), drag the selected light's aim square to aim it and an area light's
// circle to turn it about its normal,
// drag elsewhere to orbit, wheel to zoom. Keys
// (thesis 6.3): arrows move the selected light up/down and sideways,
// Home/End forwards/backwards in this view's frame, Shift ten times
// further; Delete deletes. The view only asks (signals); the main window
// makes the edits.
#pragma once

#include <QImage>
#include <QWidget>
#include <optional>
#include <vector>

#include "gui/lighting_document.h"

namespace relight::gui {

// Boxes of the given sizes beside their anchors (markers), each on the first
// side (right, left, above, below, then further out to the right) where it
// overlaps no box placed before it.
std::vector<QRectF> place_labels(const std::vector<QPointF>& anchors, const std::vector<QSizeF>& sizes);

class GeometryView : public QWidget {
  Q_OBJECT

 public:
  explicit GeometryView(QWidget* parent = nullptr);
  void set_document(LightingDocument* document);
  void set_selected(int index);
  int selected() const { return selected_; }

  // The orbit: degrees about the world up from the photo camera's heading,
  // degrees looking down, metres from the scene's centre.
  void set_orbit(float yaw_deg, float pitch_deg, float distance);
  // The first view: what the photo's camera sees (the middle 80 % of its
  // pixels' surfaces along each axis, so that a ground to the horizon does
  // not fill the view), with the lights and the camera, from above the
  // camera's heading.
  void reset_orbit();
  void frame_all();       // the whole geometry
  void frame_selected();  // the selected light, nearer, from where the view looks

  // The frame the keys move lights in: world up, and this view's heading
  // made horizontal (forward) with its horizontal right.
  struct MoveFrame {
    Vec3 right, up, forward;
  };
  MoveFrame move_frame() const;
  // Metres one key press moves a light (Shift: ten times this): about 1 % of
  // the scene's size, rounded to 1, 2 or 5 times a power of ten.
  float move_step() const { return move_step_; }
  // The move of a key press (arrows, Home, End, with Shift), if it is one.
  std::optional<Vec3> key_move(int key, Qt::KeyboardModifiers modifiers) const;

  Vec3 eye_position() const { return eye().position; }  // the orbit's viewpoint
  // Where a world point appears in the widget, if in front of the eye.
  std::optional<QPointF> project(const Vec3& p) const;
  // Where light `index`'s dot is drawn (a sun's: out along where it shines from).
  Vec3 marker_position(const Light& light) const;
  // A spot's or area light's aim handle (a square, drawn for the selected
  // light): where its aim meets the first surface; dragged, it re-aims the
  // light through the point dragged to.
  std::optional<Vec3> aim_point(const Light& light) const;

  QSize sizeHint() const override { return {420, 320}; }
  QSize minimumSizeHint() const override { return {200, 150}; }

 signals:
  void lightClicked(int index);
  // While a dot is dragged: the light as it now is; at the release, before and after.
  void lightDragged(int index, const relight::Light& light);
  void lightDropped(int index, const relight::Light& before, const relight::Light& after);
  void moveRequested(const relight::Vec3& delta);
  void deleteRequested();

 protected:
  void paintEvent(QPaintEvent* event) override;
  void resizeEvent(QResizeEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;
  void wheelEvent(QWheelEvent* event) override;
  void keyPressEvent(QKeyEvent* event) override;

 private:
  struct Eye {
    Vec3 position, forward, right, up;
    float focal = 1.0f;  // pixels
  };
  Eye eye() const;
  Vec3 heading() const;  // horizontal, unit
  void draw_mesh();      // into mesh_image_
  // A name drawn beside a marker.
  struct Label {
    QPointF anchor;
    QString text;
  };
  void draw_camera(QPainter& painter, std::vector<Label>& labels) const;
  void draw_lights(QPainter& painter, std::vector<Label>& labels) const;
  float shape_reach(const Light& light) const;  // a spot's cone's length, a sun's arrow's
  // Each label on a dark box beside its marker (place_labels).
  void draw_labels(QPainter& painter, const std::vector<Label>& labels) const;
  int light_at(const QPointF& point) const;
  // Whether the widget point is on the selected light's handle at `handle`.
  bool on_handle(const QPointF& point, const std::optional<Vec3>& handle) const;
  // A point dragged by `by` pixels in the plane through it facing the view.
  Vec3 dragged(const Vec3& start, const QPointF& by) const;
  // A sun whose marker (on a sphere about the centre) is under the widget
  // point: its direction from there through the centre.
  Light sun_dragged_to(const Light& sun, const QPointF& point) const;
  void geometry_changed();

  LightingDocument* document_ = nullptr;
  int selected_ = -1;
  Vec3 world_up_ = Vec3::UnitZ(), reference_heading_ = Vec3::UnitY(), centre_ = Vec3::Zero();
  // scene_size_: the size of what the camera sees, which sets the steps,
  // the markers and the first view's distance.
  float scene_size_ = 1.0f, move_step_ = 0.01f;
  Vec3 seen_centre_ = Vec3::Zero();
  float yaw_deg_ = 0.0f, pitch_deg_ = 35.0f, distance_ = 1.0f;
  QImage mesh_image_;  // the shaded mesh for the current orbit and size
  enum class Drag { none, orbit, light, aim, turn, sun } drag_ = Drag::none;
  QPointF drag_start_;
  float drag_yaw_ = 0.0f, drag_pitch_ = 0.0f;
  Light drag_light_;
  Vec3 drag_handle_ = Vec3::Zero();  // the aim or turn handle where the drag started
};

}  // namespace relight::gui
