#include "gui/task_status.h"

#include <QHBoxLayout>
#include <QLabel>
#include <QProgressBar>
#include <QToolButton>

#include "core/progress.h"
#include "gui/background_task.h"

namespace relight::gui {

TaskStatus::TaskStatus(BackgroundTask& task, QWidget* parent)
    : QWidget(parent), label_(new QLabel), progress_(new QProgressBar), left_(new QLabel) {
  progress_->setRange(0, 100);
  progress_->setMaximumWidth(220);
  auto* cancel = new QToolButton;
  cancel->setText(tr("Cancel"));
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(label_);
  layout->addWidget(progress_);
  layout->addWidget(left_);
  layout->addWidget(cancel);
  connect(cancel, &QToolButton::clicked, &task, &BackgroundTask::cancel);
  connect(&task, &BackgroundTask::progressed, this, &TaskStatus::show_progress);
  connect(&task, &BackgroundTask::finished, this, &QWidget::hide);
  hide();
}

void TaskStatus::show_task(const QString& label) {
  label_->setText(label);
  progress_->setValue(0);
  left_->clear();
  show();
}

void TaskStatus::show_progress(int percent, std::optional<double> seconds_left) {
  progress_->setValue(percent);
  left_->setText(seconds_left ? tr("~%1 left").arg(QString::fromStdString(duration_text(*seconds_left))) : QString());
}

}  // namespace relight::gui
