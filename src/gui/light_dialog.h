// LightDialog (thesis 6.3): the dialog that adds a light or changes one —
// description, colour (hex field and colour picker), type, position,
// direction, power and the type's shape (spot angle and blend, area size,
// radius, sun angle). It checks the values as they are typed, says what is
// wrong in words and keeps OK disabled until they are right. Fields the
// user did not touch keep the light's exact values (the form shows them
// rounded).
#pragma once

#include <QDialog>

#include "scene/light.h"

class QComboBox;
class QDialogButtonBox;
class QDoubleSpinBox;
class QFormLayout;
class QLabel;
class QLineEdit;
class QToolButton;

namespace relight::gui {

class LightDialog : public QDialog {
  Q_OBJECT

 public:
  explicit LightDialog(QWidget* parent = nullptr);

  void set_light(const Light& light);
  // The light as the form describes it.
  Light light() const;
  // What is wrong with the form, in one sentence; empty when it is valid.
  QString validation_error() const;

 private:
  struct Vec3Boxes {
    QDoubleSpinBox* x;
    QDoubleSpinBox* y;
    QDoubleSpinBox* z;
  };
  QWidget* vec3_row(Vec3Boxes& boxes, const QString& name, double range, int decimals, const QString& unit);
  void show_rows_for_type();
  void update_validation();
  void pick_colour();
  void update_swatch();

  Light original_;
  QFormLayout* form_;
  QLineEdit* description_;
  QComboBox* type_;
  QLineEdit* colour_hex_;
  QToolButton* colour_button_;
  Vec3Boxes position_, direction_;
  QWidget* position_row_;
  QWidget* direction_row_;
  QDoubleSpinBox* power_;
  QLabel* power_label_;
  QDoubleSpinBox* spot_angle_;
  QDoubleSpinBox* blend_;
  QDoubleSpinBox* width_;
  QDoubleSpinBox* height_;
  QWidget* size_row_;
  QDoubleSpinBox* radius_;
  QDoubleSpinBox* sun_angle_;
  QLabel* error_;
  QDialogButtonBox* buttons_;
};

}  // namespace relight::gui
