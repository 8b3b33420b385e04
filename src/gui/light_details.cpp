#include "gui/light_details.h"

#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QSignalBlocker>
#include <cmath>

#include "gui/colour_temperature.h"
#include "gui/tone_map.h"

namespace relight::gui {

namespace {

constexpr double kMaxLightStops = 20.0;

QString vec3_text(const Vec3& v, const QString& unit) {
  return QStringLiteral("%1, %2, %3%4")
      .arg(double(v.x()), 0, 'f', 3)
      .arg(double(v.y()), 0, 'f', 3)
      .arg(double(v.z()), 0, 'f', 3)
      .arg(unit);
}

QLabel* detail_label(const QString& name) {
  auto* label = new QLabel(QStringLiteral("\u2014"));
  label->setObjectName(name);
  label->setTextInteractionFlags(Qt::TextSelectableByMouse);
  return label;
}

// A field that announces a value when it is stepped or typed and confirmed
// (Enter, or leaving it), not at every key; a typed value out of range is
// set to the nearest end of it, where the field shows it.
QDoubleSpinBox* edit_field(const QString& name, double min, double max, int decimals, double step,
                           const QString& tip) {
  auto* box = new QDoubleSpinBox;
  box->setObjectName(name);
  box->setRange(min, max);
  box->setDecimals(decimals);
  box->setSingleStep(step);
  box->setKeyboardTracking(false);
  box->setCorrectionMode(QAbstractSpinBox::CorrectToNearestValue);
  box->setToolTip(tip);
  box->setEnabled(false);
  return box;
}

QWidget* field_row(std::initializer_list<QWidget*> widgets) {
  auto* row = new QWidget;
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  for (QWidget* w : widgets) layout->addWidget(w);
  layout->addStretch(1);
  return row;
}

float power_of(const Light& light) { return light.type == LightType::directional ? light.irradiance : light.power; }

}  // namespace

LightDetails::LightDetails(QWidget* parent)
    : QGroupBox(tr("Selected light"), parent),
      type_(detail_label("detail_type")),
      colour_(detail_label("detail_colour")),
      position_(detail_label("detail_position")),
      direction_(detail_label("detail_direction")),
      power_(detail_label("detail_power")),
      stops_reference_(new QLabel),
      temperature_(edit_field("temperature", kMinKelvin, kMaxKelvin, 0, 100,
                              tr("The colour of a blackbody at this temperature, %1\u2013%2 K")
                                  .arg(double(kMinKelvin))
                                  .arg(double(kMaxKelvin)))),
      tint_(edit_field("tint", -kMaxTint, kMaxTint, 3, 0.001,
                       tr("Off the blackbody colours: + towards green, \u2212 towards magenta (Duv, %1 at most)")
                           .arg(double(kMaxTint)))),
      stops_(edit_field("stops", -kMaxLightStops, kMaxLightStops, 2, 1.0,
                        tr("Stops from the power the light had when selected: +1 doubles it, \u22121 halves it"))) {
  temperature_->setSuffix(tr(" K"));
  stops_->setSuffix(tr(" EV"));
  stops_reference_->setObjectName("stops_reference");
  auto* form = new QFormLayout(this);
  form->setLabelAlignment(Qt::AlignRight);
  form->addRow(tr("Type"), type_);
  form->addRow(tr("Colour"), colour_);
  form->addRow(tr("Temperature"), field_row({temperature_, new QLabel(tr("tint")), tint_}));
  form->addRow(tr("Position"), position_);
  form->addRow(tr("Direction"), direction_);
  form->addRow(tr("Power"), power_);
  form->addRow(tr("Stops"), field_row({stops_, stops_reference_}));
  connect(temperature_, &QDoubleSpinBox::valueChanged, this, &LightDetails::edit_temperature);
  connect(tint_, &QDoubleSpinBox::valueChanged, this, &LightDetails::edit_temperature);
  connect(stops_, &QDoubleSpinBox::valueChanged, this,
          [this](double stops) { emit powerEdited(reference_power_ * float(std::exp2(stops))); });
}

void LightDetails::edit_temperature() {
  temperature_colour_ = colour_from_temperature(float(temperature_->value()), float(tint_->value()));
  emit colourEdited(*temperature_colour_);
}

void LightDetails::show_light(const Light* light) {
  reference_power_ = light ? power_of(*light) : 0.0f;
  temperature_colour_.reset();
  temperature_->setEnabled(light);
  tint_->setEnabled(light);
  if (light) {
    refresh_light(*light);
    return;
  }
  for (QLabel* label : {type_, colour_, position_, direction_, power_}) label->setText(QStringLiteral("\u2014"));
  stops_reference_->clear();
  stops_->setEnabled(false);
}

void LightDetails::refresh_light(const Light& l) {
  const bool sun = l.type == LightType::directional;
  type_->setText(sun ? tr("sun") : QString(to_string(l.type)));
  colour_->setText(QStringLiteral("<span style='color:%1'>\u25a0</span> %2 (%3, %4, %5)")
                       .arg(display_colour(l.color).name(), colour_hex(l.color))
                       .arg(double(l.color.x()), 0, 'g', 3)
                       .arg(double(l.color.y()), 0, 'g', 3)
                       .arg(double(l.color.z()), 0, 'g', 3));
  position_->setText(sun ? tr("\u2014 (infinitely far)") : vec3_text(l.position, tr(" m")));
  direction_->setText(l.type == LightType::point ? tr("\u2014 (all around)") : vec3_text(l.direction, {}));
  const QString unit = sun ? tr("W/m\u00b2") : tr("W");
  power_->setText(QStringLiteral("%1 %2").arg(double(power_of(l)), 0, 'g', 4).arg(unit));

  // Showing values is not editing them: the fields stay quiet.
  const QSignalBlocker quiet_temperature(temperature_), quiet_tint(tint_), quiet_stops(stops_);
  if (l.color != temperature_colour_) {
    // Black has no temperature: the fields keep what they show, to set one from.
    if (const std::optional<ColourTemperature> temperature = temperature_of_colour(l.color)) {
      temperature_->setValue(double(temperature->kelvin));
      tint_->setValue(double(temperature->tint));
    }
    temperature_colour_ = l.color;
  }
  const bool stops = reference_power_ > 0.0f && power_of(l) > 0.0f;
  stops_->setEnabled(stops);
  if (stops) stops_->setValue(std::log2(double(power_of(l)) / double(reference_power_)));
  stops_reference_->setText(tr("EV 0 = %1 %2").arg(double(reference_power_), 0, 'g', 4).arg(unit));
}

}  // namespace relight::gui
