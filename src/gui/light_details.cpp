#include "gui/light_details.h"

#include <QFormLayout>
#include <QLabel>

#include "gui/tone_map.h"

namespace relight::gui {

namespace {

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

}  // namespace

LightDetails::LightDetails(QWidget* parent)
    : QGroupBox(tr("Selected light"), parent),
      type_(detail_label("detail_type")),
      colour_(detail_label("detail_colour")),
      position_(detail_label("detail_position")),
      direction_(detail_label("detail_direction")),
      power_(detail_label("detail_power")) {
  auto* form = new QFormLayout(this);
  form->setLabelAlignment(Qt::AlignRight);
  form->addRow(tr("Type"), type_);
  form->addRow(tr("Colour"), colour_);
  form->addRow(tr("Position"), position_);
  form->addRow(tr("Direction"), direction_);
  form->addRow(tr("Power"), power_);
}

void LightDetails::show_light(const Light* light) {
  for (QLabel* label : {type_, colour_, position_, direction_, power_})
    label->setText(light ? QString() : QStringLiteral("\u2014"));
  if (!light) return;
  const Light& l = *light;
  const bool sun = l.type == LightType::directional;
  type_->setText(sun ? tr("sun") : QString(to_string(l.type)));
  colour_->setText(QStringLiteral("<span style='color:%1'>\u25a0</span> %2 (%3, %4, %5)")
                       .arg(display_colour(l.color).name(), colour_hex(l.color))
                       .arg(double(l.color.x()), 0, 'g', 3)
                       .arg(double(l.color.y()), 0, 'g', 3)
                       .arg(double(l.color.z()), 0, 'g', 3));
  position_->setText(sun ? tr("\u2014 (infinitely far)") : vec3_text(l.position, tr(" m")));
  direction_->setText(l.type == LightType::point ? tr("\u2014 (all around)") : vec3_text(l.direction, {}));
  power_->setText(sun ? tr("%1 W/m\u00b2").arg(double(l.irradiance), 0, 'g', 4)
                      : tr("%1 W").arg(double(l.power), 0, 'g', 4));
}

}  // namespace relight::gui
