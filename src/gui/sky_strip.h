// SkyStrip: a new environment as a strip, for the Environment entry: the
// whole sky as an equirect-style thumbnail (azimuth across, up at the top),
// tone-mapped, laid out about the sky's up as it is turned; a sideways drag
// turns it, the strip's width being a full turn, so that the sky follows
// the mouse. The turn comes out as signals, for the window to make
// undoable.
#pragma once

#include <QImage>
#include <QWidget>
#include <memory>
#include <optional>

#include "scene/scene.h"

namespace relight::gui {

// `sky`'s image resampled to an equirect of width x width/2 in the sky's own
// frame (whatever its mapping) and tone-mapped for display: scaled to a
// mean luminance of 1/2, then x / (1 + x), sRGB.
QImage sky_thumbnail(const Probe& sky, int width);

class SkyStrip : public QWidget {
  Q_OBJECT

 public:
  explicit SkyStrip(QWidget* parent = nullptr);
  // The sky shown (none: the scene's own environment, which has no strip),
  // turned by turn_deg counter-clockwise seen from above. The thumbnail is
  // made again only for another image.
  void set_sky(const std::optional<RigEnvironment>& sky, float turn_deg);
  float turn_deg() const { return turn_deg_; }
  QSize sizeHint() const override { return {320, 64}; }
  QSize minimumSizeHint() const override { return {120, 40}; }

 signals:
  void turnDragged(float turn_deg);                     // while the mouse is down
  void turnDropped(float before_deg, float after_deg);  // let go, after a turn

 protected:
  void paintEvent(QPaintEvent* event) override;
  void mousePressEvent(QMouseEvent* event) override;
  void mouseMoveEvent(QMouseEvent* event) override;
  void mouseReleaseEvent(QMouseEvent* event) override;

 private:
  float turn_under_mouse(const QMouseEvent& event) const;

  std::shared_ptr<const Probe> image_;  // the thumbnail's
  std::optional<Vec3> colour_;          // a constant environment's
  QImage thumbnail_;
  float turn_deg_ = 0.0f;
  std::optional<float> drag_start_turn_;
  double drag_start_x_ = 0.0;
};

// A turn in degrees brought into [-180, 180).
float wrapped_turn(float degrees);

}  // namespace relight::gui
