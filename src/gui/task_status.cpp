#include "gui/task_status.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QToolButton>

#include "gui/background_task.h"

namespace relight::gui {

TaskStatus::TaskStatus(BackgroundTask& task, QWidget* parent)
    : QWidget(parent), label_(new QLabel), progress_(new QProgressBar) {
  progress_->setRange(0, 100);
  progress_->setMaximumWidth(220);
  auto* cancel = new QToolButton;
  cancel->setText(tr("Cancel"));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(label_);
  layout->addWidget(progress_);
  layout->addWidget(cancel);
  connect(cancel, &QToolButton::clicked, &task, &BackgroundTask::cancel);
  connect(&task, &BackgroundTask::progressed, progress_, &QProgressBar::setValue);
  connect(&task, &BackgroundTask::finished, this, &QWidget::hide);
  hide();
}

void TaskStatus::show_task(const QString& label) {
  label_->setText(label);
  progress_->setValue(0);
  show();
}

}  // namespace relight::gui
