// EnvironmentEntry: the rig's environment at the head of the light list —
// an eye that switches a new sky off (the scene's own environment lights
// instead) and on, its name with an Image… button to choose an HDRI, the
// sky as a strip to drag sideways to turn it (SkyStrip), its turn in
// degrees and its strength in stops (environment_scale, 0 EV = x1). It
// shows a document; edits come out as signals, for the window to make
// undoable.
#pragma once

#include <QFrame>

class QDoubleSpinBox;
class QLabel;
class QToolButton;
class QPushButton;

namespace relight::gui {

class LightingDocument;
class SkyStrip;

class EnvironmentEntry : public QFrame {
  Q_OBJECT

 public:
  explicit EnvironmentEntry(QWidget* parent = nullptr);
  // Follows `document` (null: nothing to edit).
  void set_document(LightingDocument* document);
  SkyStrip& strip() const { return *strip_; }

 signals:
  void imageRequested();
  void enabledToggled(bool enabled);
  void turnDragged(float turn_deg);
  void turnDropped(float before_deg, float after_deg);
  void turnEdited(float turn_deg);
  void strengthEdited(float environment_scale);

 private:
  void refresh();

  LightingDocument* document_ = nullptr;
  QToolButton* eye_;
  QLabel* name_;
  QPushButton* image_button_;
  SkyStrip* strip_;
  QDoubleSpinBox *turn_, *stops_;
};

}  // namespace relight::gui
