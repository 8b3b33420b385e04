#include "gui/photo_panel.h"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QSlider>
#include <QVBoxLayout>

#include "gui/photo_view.h"

namespace relight::gui {

PhotoPanel::PhotoPanel(QWidget* parent)
    : QWidget(parent),
      photo_(new PhotoView),
      split_(new QSlider(Qt::Horizontal)),
      exposure_(new QDoubleSpinBox),
      ambient_(new QDoubleSpinBox),
      quality_(new QLabel) {
  photo_->setObjectName("photo_view");
  split_->setObjectName("split");
  split_->setRange(0, 100);
  split_->setToolTip(tr("Drag right to show the photo as taken left of a line, the re-lit photo right of it"));
  connect(split_, &QSlider::valueChanged, this, [this](int value) { photo_->set_split(value / 100.0); });
  exposure_->setObjectName("exposure");
  exposure_->setRange(-10.0, 10.0);
  exposure_->setSingleStep(0.5);
  exposure_->setDecimals(1);
  exposure_->setSuffix(tr(" EV"));
  exposure_->setToolTip(tr("Display exposure in stops (PNG export uses it too)"));
  connect(exposure_, &QDoubleSpinBox::valueChanged, this, [this](double ev) { photo_->set_exposure(float(ev)); });
  ambient_->setObjectName("ambient");
  ambient_->setRange(0.0, 20.0);
  ambient_->setSingleStep(0.1);
  ambient_->setDecimals(2);
  ambient_->setPrefix(QStringLiteral("\u00d7 "));
  ambient_->setToolTip(tr("Light from the environment (probes, background) and what is outside the geometry"));
  connect(ambient_, &QDoubleSpinBox::valueChanged, this, [this](double scale) { emit ambientEdited(float(scale)); });
  quality_->setObjectName("quality");
  quality_->setMinimumWidth(220);
  quality_->setAlignment(Qt::AlignRight | Qt::AlignVCenter);

  auto* controls = new QHBoxLayout;
  controls->setSpacing(10);
  controls->addWidget(new QLabel(tr("Compare with photo")));
  controls->addWidget(split_, 1);
  controls->addSpacing(16);
  controls->addWidget(new QLabel(tr("Exposure")));
  controls->addWidget(exposure_);
  controls->addSpacing(16);
  controls->addWidget(new QLabel(tr("Ambient")));
  controls->addWidget(ambient_);
  controls->addSpacing(16);
  controls->addWidget(quality_);

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(2, 6, 6, 6);
  layout->addWidget(photo_, 1);
  layout->addLayout(controls);
}

void PhotoPanel::show_ambient(float scale) {
  const QSignalBlocker block(ambient_);
  ambient_->setValue(double(scale));
}

void PhotoPanel::set_exposure(float stops) { exposure_->setValue(double(stops)); }

void PhotoPanel::enable_ambient(bool enabled) { ambient_->setEnabled(enabled); }

void PhotoPanel::show_quality(FrameQuality quality, Backend backend) {
  const char* name = backend == Backend::gl ? "OpenGL" : "CPU";
  switch (quality) {
    case FrameQuality::interactive:
      quality_->setText(tr("Preview (%1)").arg(name));
      break;
    case FrameQuality::refining:
      quality_->setText(tr("Refining\u2026 (%1)").arg(name));
      break;
    case FrameQuality::converged:
      quality_->setText(tr("Final quality (%1)").arg(name));
      break;
  }
}

}  // namespace relight::gui
