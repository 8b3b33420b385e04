// The selected light's details in the main window: type, colour, position,
// direction and power, as text that can be selected and copied.
#pragma once

#include <QGroupBox>

#include "scene/light.h"

class QLabel;

namespace relight::gui {

class LightDetails : public QGroupBox {
  Q_OBJECT

 public:
  explicit LightDetails(QWidget* parent = nullptr);
  // Shows `light`, or dashes where it is null (nothing selected).
  void show_light(const Light* light);

 private:
  QLabel *type_, *colour_, *position_, *direction_, *power_;
};

}  // namespace relight::gui
