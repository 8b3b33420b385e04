#include "gui/light_dialog.h"

#include <QColorDialog>
#include <QComboBox>
#include <QDialogButtonBox>
#include <QDoubleSpinBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QToolButton>
#include <QVBoxLayout>
#include <algorithm>
#include <cmath>

#include "gui/tone_map.h"

namespace relight::gui {

namespace {

constexpr LightType kTypes[] = {LightType::point, LightType::spot, LightType::area, LightType::directional};

QDoubleSpinBox* spin_box(const QString& name, double min, double max, int decimals, const QString& unit) {
  auto* box = new QDoubleSpinBox;
  box->setObjectName(name);
  box->setRange(min, max);
  box->setDecimals(decimals);
  box->setSuffix(unit);
  box->setSingleStep(std::pow(10.0, -decimals + 1));
  box->setAccelerated(true);
  return box;
}

// Shows `value` and remembers what was shown, so that light() can tell an
// untouched field (keep the exact value) from an edited one.
void show_value(QDoubleSpinBox* box, float value) {
  box->setValue(double(value));
  box->setProperty("shown", box->value());
}

void take_value(float& field, const QDoubleSpinBox* box) {
  if (box->value() != box->property("shown").toDouble()) field = float(box->value());
}

}  // namespace

LightDialog::LightDialog(QWidget* parent) : QDialog(parent) {
  setWindowTitle(tr("Light"));
  form_ = new QFormLayout;
  form_->setLabelAlignment(Qt::AlignRight | Qt::AlignVCenter);
  form_->setHorizontalSpacing(12);
  form_->setVerticalSpacing(8);

  description_ = new QLineEdit;
  description_->setObjectName("description");
  description_->setPlaceholderText(tr("e.g. key light, window, desk lamp"));
  form_->addRow(tr("&Description"), description_);

  type_ = new QComboBox;
  type_->setObjectName("type");
  for (const char* name : {"Point", "Spot", "Area", "Sun"}) type_->addItem(tr(name));
  form_->addRow(tr("&Type"), type_);

  colour_hex_ = new QLineEdit;
  colour_hex_->setObjectName("colour");
  colour_hex_->setPlaceholderText("#ffd9a0");
  colour_hex_->setMaxLength(7);
  colour_button_ = new QToolButton;
  colour_button_->setObjectName("pick_colour");
  colour_button_->setText(tr("Pick\u2026"));
  colour_button_->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  auto* colour_row = new QWidget;
  auto* colour_layout = new QHBoxLayout(colour_row);
  colour_layout->setContentsMargins(0, 0, 0, 0);
  colour_layout->addWidget(colour_hex_, 1);
  colour_layout->addWidget(colour_button_);
  form_->addRow(tr("&Colour"), colour_row);

  position_row_ = vec3_row(position_, "position", 1000.0, 3, tr(" m"));
  form_->addRow(tr("&Position"), position_row_);
  direction_row_ = vec3_row(direction_, "direction", 1.0, 3, QString());
  form_->addRow(tr("D&irection"), direction_row_);

  power_ = spin_box("power", 0.0, 1e7, 2, tr(" W"));
  power_label_ = new QLabel(tr("Po&wer"));
  power_label_->setBuddy(power_);
  form_->addRow(power_label_, power_);
  spot_angle_ = spin_box("spot_angle", 1.0, 179.0, 1, tr("\u00b0"));
  form_->addRow(tr("Spot &angle"), spot_angle_);
  blend_ = spin_box("blend", 0.0, 1.0, 2, QString());
  blend_->setToolTip(tr("Softness of the cone's edge: 0 hard, 1 soft"));
  form_->addRow(tr("&Blend"), blend_);
  width_ = spin_box("width", 0.0, 100.0, 3, tr(" m"));
  height_ = spin_box("height", 0.0, 100.0, 3, tr(" m"));
  size_row_ = new QWidget;
  auto* size_layout = new QHBoxLayout(size_row_);
  size_layout->setContentsMargins(0, 0, 0, 0);
  size_layout->addWidget(width_, 1);
  size_layout->addWidget(new QLabel(QStringLiteral("\u00d7")), 0);
  size_layout->addWidget(height_, 1);
  form_->addRow(tr("Area &size"), size_row_);
  radius_ = spin_box("radius", 0.0, 10.0, 3, tr(" m"));
  radius_->setToolTip(tr("0: a hard point; larger: softer shadows"));
  form_->addRow(tr("&Radius"), radius_);
  sun_angle_ = spin_box("sun_angle", 0.0, 45.0, 2, tr("\u00b0"));
  sun_angle_->setToolTip(tr("Angular diameter of the sun: 0 hard shadows, 0.53\u00b0 the real sun"));
  form_->addRow(tr("Sun an&gle"), sun_angle_);

  error_ = new QLabel;
  error_->setObjectName("error");
  error_->setStyleSheet("color: #b00020;");
  error_->setWordWrap(true);
  buttons_ = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);

  auto* layout = new QVBoxLayout(this);
  layout->addLayout(form_);
  layout->addWidget(error_);
  layout->addWidget(buttons_);

  connect(buttons_, &QDialogButtonBox::accepted, this, &QDialog::accept);
  connect(buttons_, &QDialogButtonBox::rejected, this, &QDialog::reject);
  connect(colour_button_, &QToolButton::clicked, this, &LightDialog::pick_colour);
  connect(type_, &QComboBox::currentIndexChanged, this, [this] {
    show_rows_for_type();
    update_validation();
  });
  connect(description_, &QLineEdit::textChanged, this, &LightDialog::update_validation);
  connect(colour_hex_, &QLineEdit::textChanged, this, [this] {
    update_swatch();
    update_validation();
  });
  for (QDoubleSpinBox* box : findChildren<QDoubleSpinBox*>())
    connect(box, &QDoubleSpinBox::valueChanged, this, &LightDialog::update_validation);
  set_light(Light{});
}

QWidget* LightDialog::vec3_row(Vec3Boxes& boxes, const QString& name, double range, int decimals,
                               const QString& unit) {
  auto* row = new QWidget;
  auto* layout = new QHBoxLayout(row);
  layout->setContentsMargins(0, 0, 0, 0);
  QDoubleSpinBox** targets[] = {&boxes.x, &boxes.y, &boxes.z};
  const char* axes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    *targets[i] = spin_box(name + "_" + axes[i], -range, range, decimals, unit);
    (*targets[i])->setPrefix(QStringLiteral("%1 ").arg(axes[i]));
    layout->addWidget(*targets[i]);
  }
  return row;
}

void LightDialog::set_light(const Light& light) {
  original_ = light;
  description_->setText(QString::fromStdString(light.name));
  type_->setCurrentIndex(int(std::find(std::begin(kTypes), std::end(kTypes), light.type) - std::begin(kTypes)));
  colour_hex_->setText(colour_hex(light.color));
  colour_hex_->setProperty("shown", colour_hex_->text());
  for (int i = 0; i < 3; ++i) {
    show_value(i == 0 ? position_.x : i == 1 ? position_.y : position_.z, light.position[i]);
    show_value(i == 0 ? direction_.x : i == 1 ? direction_.y : direction_.z, light.direction[i]);
  }
  show_value(power_, light.type == LightType::directional ? light.irradiance : light.power);
  show_value(spot_angle_, light.spot_angle_deg);
  show_value(blend_, light.blend);
  show_value(width_, light.size.x());
  show_value(height_, light.size.y());
  show_value(radius_, light.radius);
  show_value(sun_angle_, light.angle_deg);
  show_rows_for_type();
  update_validation();
}

Light LightDialog::light() const {
  Light l = original_;
  l.name = description_->text().trimmed().toStdString();
  l.type = kTypes[std::max(0, type_->currentIndex())];
  if (colour_hex_->text() != colour_hex_->property("shown").toString())
    if (const auto c = colour_from_hex(colour_hex_->text())) l.color = *c;
  take_value(l.position.x(), position_.x);
  take_value(l.position.y(), position_.y);
  take_value(l.position.z(), position_.z);
  take_value(l.direction.x(), direction_.x);
  take_value(l.direction.y(), direction_.y);
  take_value(l.direction.z(), direction_.z);
  take_value(l.type == LightType::directional ? l.irradiance : l.power, power_);
  take_value(l.spot_angle_deg, spot_angle_);
  take_value(l.blend, blend_);
  take_value(l.size.x(), width_);
  take_value(l.size.y(), height_);
  take_value(l.radius, radius_);
  take_value(l.angle_deg, sun_angle_);
  return l;
}

QString LightDialog::validation_error() const {
  if (description_->text().trimmed().isEmpty()) return tr("Description: give the light a short name.");
  if (!colour_from_hex(colour_hex_->text()))
    return tr("Colour: \u201c%1\u201d is not a colour; expected # and six hex digits, e.g. #ffd9a0.")
        .arg(colour_hex_->text());
  const Light l = light();
  if (l.type != LightType::point && l.direction.norm() < 1e-6f)
    return tr("Direction: must not be zero (it is where the light points).");
  if (l.type == LightType::area) {
    if (l.size.x() <= 0.0f || l.size.y() <= 0.0f) return tr("Area size: width and height must be above 0 m.");
    if (l.direction.normalized().cross(l.up.normalized()).norm() < 1e-3f)
      return tr("Direction: an area light must not point along its up axis (%1, %2, %3).")
          .arg(double(l.up.x()))
          .arg(double(l.up.y()))
          .arg(double(l.up.z()));
  }
  return {};
}

void LightDialog::show_rows_for_type() {
  const LightType type = kTypes[std::max(0, type_->currentIndex())];
  const bool sun = type == LightType::directional;
  form_->setRowVisible(position_row_, !sun);
  form_->setRowVisible(direction_row_, type != LightType::point);
  power_label_->setText(sun ? tr("Irradiance") : tr("Po&wer"));
  power_->setSuffix(sun ? tr(" W/m\u00b2") : tr(" W"));
  form_->setRowVisible(spot_angle_, type == LightType::spot);
  form_->setRowVisible(blend_, type == LightType::spot);
  form_->setRowVisible(size_row_, type == LightType::area);
  form_->setRowVisible(radius_, type == LightType::point || type == LightType::spot);
  form_->setRowVisible(sun_angle_, sun);
  adjustSize();
}

void LightDialog::update_validation() {
  const QString error = validation_error();
  error_->setText(error);
  error_->setVisible(!error.isEmpty());
  buttons_->button(QDialogButtonBox::Ok)->setEnabled(error.isEmpty());
}

void LightDialog::pick_colour() {
  const auto current = colour_from_hex(colour_hex_->text());
  const QColor picked = QColorDialog::getColor(display_colour(current.value_or(original_.color)), this,
                                               tr("Light colour"));
  if (picked.isValid()) colour_hex_->setText(picked.name());
}

void LightDialog::update_swatch() {
  const auto colour = colour_from_hex(colour_hex_->text());
  QPixmap swatch(16, 16);
  swatch.fill(colour ? display_colour(*colour) : QColor(Qt::transparent));
  colour_button_->setIcon(QIcon(swatch));
}

}  // namespace relight::gui
