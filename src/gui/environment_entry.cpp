#include "gui/environment_entry.h"

#include <QDoubleSpinBox>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QLabel>
#include <QPushButton>
#include <QSignalBlocker>
#include <QToolButton>
#include <QVBoxLayout>
#include <cmath>

#include "gui/light_list_model.h"
#include "gui/lighting_document.h"
#include "gui/sky_strip.h"
#include "gui/tone_map.h"

namespace relight::gui {

namespace {

constexpr double kMaxStops = 10.0;

QString sky_name(const SkyEdit& sky) {
  if (!sky.opened) return QObject::tr("the scene's own");
  if (!sky.opened->image) return QObject::tr("constant %1").arg(colour_hex(sky.opened->color));
  return QFileInfo(QString::fromStdString(sky.opened->image->path)).fileName();
}

}  // namespace

EnvironmentEntry::EnvironmentEntry(QWidget* parent)
    : QFrame(parent),
      eye_(new QToolButton),
      name_(new QLabel),
      image_button_(new QPushButton(tr("&Image\u2026"))),
      strip_(new SkyStrip),
      turn_(new QDoubleSpinBox),
      stops_(new QDoubleSpinBox) {
  setFrameShape(QFrame::StyledPanel);
  eye_->setObjectName("environment_eye");
  name_->setObjectName("environment_name");
  image_button_->setObjectName("environment_image");
  strip_->setObjectName("environment_strip");
  turn_->setObjectName("environment_turn");
  stops_->setObjectName("environment_stops");
  eye_->setAutoRaise(true);
  eye_->setIconSize(QSize(20, 20));
  eye_->setToolTip(tr("Switch the new sky off (the scene's own environment lights) or on"));
  image_button_->setToolTip(tr("Light the scene with an HDR image (equirect or mirror ball)"));
  turn_->setRange(-180.0, 180.0);
  turn_->setWrapping(true);
  turn_->setDecimals(1);
  turn_->setSingleStep(5.0);
  turn_->setSuffix(tr("\u00b0"));
  turn_->setKeyboardTracking(false);
  turn_->setToolTip(tr("The sky turned about its up, counter-clockwise seen from above"));
  stops_->setRange(-kMaxStops, kMaxStops);
  stops_->setDecimals(2);
  stops_->setSingleStep(0.5);
  stops_->setSuffix(tr(" EV"));
  stops_->setKeyboardTracking(false);
  stops_->setToolTip(tr("The environment's strength in stops: 0 EV is as it is, +1 doubles it"));

  auto* head = new QHBoxLayout;
  head->addWidget(eye_);
  head->addWidget(new QLabel(tr("<b>Environment</b> \u2014")));
  head->addWidget(name_, 1);
  head->addWidget(image_button_);
  auto* fields = new QHBoxLayout;
  fields->addWidget(new QLabel(tr("Turn")));
  fields->addWidget(turn_);
  fields->addSpacing(12);
  fields->addWidget(new QLabel(tr("Strength")));
  fields->addWidget(stops_);
  fields->addStretch(1);
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 4, 6, 6);
  layout->addLayout(head);
  layout->addWidget(strip_);
  layout->addLayout(fields);

  connect(eye_, &QToolButton::clicked, this, [this] {
    if (document_) emit enabledToggled(!document_->sky().enabled);
  });
  connect(image_button_, &QPushButton::clicked, this, &EnvironmentEntry::imageRequested);
  connect(strip_, &SkyStrip::turnDragged, this, &EnvironmentEntry::turnDragged);
  connect(strip_, &SkyStrip::turnDropped, this, &EnvironmentEntry::turnDropped);
  connect(turn_, &QDoubleSpinBox::valueChanged, this,
          [this](double degrees) { emit turnEdited(wrapped_turn(float(degrees))); });
  connect(stops_, &QDoubleSpinBox::valueChanged, this,
          [this](double stops) { emit strengthEdited(float(std::exp2(stops))); });
  refresh();
}

void EnvironmentEntry::set_document(LightingDocument* document) {
  if (document_) disconnect(document_, nullptr, this, nullptr);
  document_ = document;
  if (document_) {
    for (auto signal : {&LightingDocument::skyChanged, &LightingDocument::rigReset})
      connect(document_, signal, this, &EnvironmentEntry::refresh);
    connect(document_, &LightingDocument::environmentScaleChanged, this, &EnvironmentEntry::refresh);
    connect(document_, &QObject::destroyed, this, [this] { set_document(nullptr); });
  }
  refresh();
}

void EnvironmentEntry::refresh() {
  const SkyEdit sky = document_ ? document_->sky() : SkyEdit{};
  const bool image = sky.opened && sky.opened->image;
  eye_->setIcon(eye_icon(sky.opened && sky.enabled, QColor(120, 170, 230)));
  eye_->setEnabled(document_ && sky.opened);
  name_->setText(sky_name(sky) + (sky.opened && !sky.enabled ? tr(" (off)") : QString()));
  image_button_->setEnabled(document_);
  strip_->set_sky(sky.enabled ? sky.opened : std::nullopt, sky.turn_deg);
  strip_->setEnabled(document_ && image && sky.enabled);
  // Showing values is not editing them: the fields stay quiet.
  const QSignalBlocker quiet_turn(turn_), quiet_stops(stops_);
  turn_->setEnabled(document_ && image && sky.enabled);
  turn_->setValue(double(sky.turn_deg));
  const float scale = document_ ? document_->rig().environment_scale : 1.0f;
  stops_->setEnabled(document_ && scale > 0.0f);
  stops_->setValue(scale > 0.0f ? std::log2(double(scale)) : -kMaxStops);
}

}  // namespace relight::gui
