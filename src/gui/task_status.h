// The status bar's view of a long task (an analysis, an export): what it
// is, how far it has got, and a Cancel button. Shown when a task starts,
// hidden when it ends.
#pragma once

#include <QWidget>

class QLabel;
class QProgressBar;

namespace relight::gui {

class BackgroundTask;

class TaskStatus : public QWidget {
  Q_OBJECT

 public:
  explicit TaskStatus(BackgroundTask& task, QWidget* parent = nullptr);
  // Shows `label` at 0 % (call as the task starts).
  void show_task(const QString& label);

 private:
  QLabel* label_;
  QProgressBar* progress_;
};

}  // namespace relight::gui
