// The status bar's view of a long task (an analysis, an export): what it
// is, how far it has got, and a Cancel button. Shown when a task starts,
// hidden when it ends.
#pragma once

#include <QWidget>
#include <optional>

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
  void show_progress(int percent, std::optional<double> seconds_left);

  QLabel* label_;
  QProgressBar* progress_;
  QLabel* left_;  // the whole task's time left, where known
};

}  // namespace relight::gui
