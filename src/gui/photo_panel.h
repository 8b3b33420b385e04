// The main window's right panel: the re-lit photo with the before/after
// split, the display exposure, the ambient (environment) level and how far
// the frame shown has got.
#pragma once

#include <QWidget>

#include "relight/session.h"

class QDoubleSpinBox;
class QLabel;
class QSlider;

namespace relight::gui {

class PhotoView;

class PhotoPanel : public QWidget {
  Q_OBJECT

 public:
  explicit PhotoPanel(QWidget* parent = nullptr);

  PhotoView& photo_view() const { return *photo_; }
  // Shows the ambient level without announcing it as an edit.
  void show_ambient(float scale);
  void enable_ambient(bool enabled);
  void show_quality(FrameQuality quality, Backend backend);
  void set_exposure(float stops);  // the display exposure, as if typed

 signals:
  void ambientEdited(float scale);  // the user set the ambient level

 private:
  PhotoView* photo_;
  QSlider* split_;
  QDoubleSpinBox *exposure_, *ambient_;
  QLabel* quality_;
};

}  // namespace relight::gui
