// The selected light's details in the main window: type, colour, position,
// direction and power, as text that can be selected and copied; and two
// ways a lighting designer gives a light: its colour as a temperature (K)
// and tint, its intensity in stops (EV) from what it was when selected.
// Edits come out as signals, for the window to make undoable.
#pragma once

#include <QGroupBox>
#include <optional>

#include "scene/light.h"

class QDoubleSpinBox;
class QLabel;

namespace relight::gui {

class LightDetails : public QGroupBox {
  Q_OBJECT

 public:
  explicit LightDetails(QWidget* parent = nullptr);
  // Shows a newly selected `light`, or dashes where it is null (nothing
  // selected); its power now is EV 0.
  void show_light(const Light* light);
  // Shows the selected light again after it changed; EV 0 stays the power it
  // had when it was selected.
  void refresh_light(const Light& light);

 signals:
  // The temperature or tint was set: the colour they give.
  void colourEdited(const relight::Vec3& colour);
  // The stops were set: the power (a sun's irradiance) they give.
  void powerEdited(float power);

 private:
  void edit_temperature();

  QLabel *type_, *colour_, *position_, *direction_, *power_, *stops_reference_;
  QDoubleSpinBox *temperature_, *tint_, *stops_;
  float reference_power_ = 0.0f;  // EV 0
  // The colour the temperature fields stand for (typed there, or estimated
  // from it): they are left as they are while the light has it.
  std::optional<Vec3> temperature_colour_;
};

}  // namespace relight::gui
