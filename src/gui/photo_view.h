// PhotoView (thesis 6.2.2): the re-lit photo, through an exposure, with a
// before/after split against the original photo (left of the split: the
// photo as taken). A click on the picture reports the pixel and the keys
// held, for selecting the light there or placing one in front of what was
// clicked. Over the picture, each light's shape (light_shapes.h) projected
// with the re-lit view's camera, coloured as in the geometry view, and, on
// demand, the geometry's edges as the camera sees them. The
// selected light's dot is a handle: dragged, the light moves across the
// surface under the cursor, keeping its height above the surface below it;
// a spot's or area light's aim (the end of its cone, a square) is another:
// dragged, it aims the light at the surface under the cursor; an area
// light's circle turns it about its normal towards where the cursor's ray
// meets the rectangle's plane.
#pragma once

#include <QImage>
#include <QWidget>
#include <memory>
#include <optional>

#include "core/image.h"
#include "scene/light.h"

namespace relight::gui {

class LightingDocument;

class PhotoView : public QWidget {
  Q_OBJECT

 public:
  explicit PhotoView(QWidget* parent = nullptr);

  void set_photo(std::shared_ptr<const Image> photo);    // before
  void set_relit(std::shared_ptr<const Image> relit);    // after
  std::shared_ptr<const Image> relit() const { return relit_; }
  void set_exposure(float stops);
  float exposure() const { return exposure_; }
  // Share of the width, from the left, that shows the original photo (0..1).
  void set_split(double share);
  double split() const { return split_; }
  // The lights whose shapes are drawn over the picture (none: no overlay).
  void set_document(LightingDocument* document);
  void set_selected(int index);
  void set_shapes_shown(bool shown);
  bool shapes_shown() const { return shapes_shown_; }
  // The geometry's edges through the photo's camera (geometry_overlay.h),
  // drawn over the picture while shown ("through the camera").
  void set_geometry_edges(QImage edges);
  void set_geometry_shown(bool shown);
  bool geometry_shown() const { return geometry_shown_; }
  // Where a sun's arrow starts: a point in front of the camera seen near
  // the picture's top-left corner, in world space.
  Vec3 sun_arrow_origin() const;

  // What is shown, at the re-lit image's size (empty before the first frame).
  const QImage& displayed_image() const { return displayed_; }
  // The pixel position in the re-lit image under a widget point, if on it.
  std::optional<QPointF> image_position(const QPointF& widget_point) const;
  // The widget point showing a position in the re-lit image (its inverse).
  QPointF widget_position(const QPointF& image_position) const;

  QSize sizeHint() const override { return {800, 600}; }

 signals:
  // A click on the picture (not on a handle), in the re-lit image's pixels (continuous).
  void photoClicked(const QPointF& position, Qt::KeyboardModifiers modifiers);
  // While a handle is dragged: the light as it now is; at the release, before and after.
  void lightDragged(int index, const relight::Light& light);
  void lightDropped(int index, const relight::Light& before, const relight::Light& after);

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;

 private:
  QRectF picture_rect() const;  // where the image is drawn: fitted, centred
  void compose();
  void draw_light_shapes(QPainter& painter) const;
  enum class Handle { none, position, aim, turn };
  // The selected light's handle at a widget point, if any, and where they are.
  Handle handle_at(const QPointF& widget_point) const;
  std::optional<QPointF> position_handle() const;
  std::optional<QPointF> aim_handle() const;
  std::optional<QPointF> turn_handle() const;  // an area light's circle
  std::optional<QPointF> shown(const Vec3& p) const;  // a world point's widget point
  std::optional<Vec3> surface_at(const QPointF& widget_point) const;
  Vec3 world_up() const;

  std::shared_ptr<const Image> photo_, relit_;
  QImage photo_image_, relit_image_, displayed_;
  QImage shown_;  // displayed_ scaled to the picture's place in the widget (made when painted)
  float exposure_ = 0.0f;
  double split_ = 0.0;
  LightingDocument* document_ = nullptr;
  int selected_ = -1;
  bool shapes_shown_ = true;
  QImage geometry_edges_;
  bool geometry_shown_ = false;
  Handle drag_ = Handle::none;
  Light drag_light_;
  float drag_height_ = 0.0f;  // the dragged light's height above the surface below it
  bool dragged_ = false;
};

}  // namespace relight::gui
