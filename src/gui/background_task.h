// BackgroundTask: long work (analysing a scene, the final render of an
// export) on a worker thread of its own that gives way to the interactive
// picture (run_giving_way, core/background_work.h), with its progress polled for a progress
// bar and a cancel that the work sees at its next progress step. Results
// come back as values: `finished` carries an empty string or the error.
#pragma once

#include <QFutureWatcher>
#include <QObject>
#include <QString>
#include <QThreadPool>
#include <QTimer>
#include <functional>
#include <memory>
#include <optional>

#include "core/progress.h"

namespace relight::gui {

class BackgroundTask : public QObject {
  Q_OBJECT

 public:
  using Work = std::function<void(Progress&)>;

  explicit BackgroundTask(QObject* parent = nullptr);
  ~BackgroundTask() override;  // cancels and waits for running work

  // Runs `work` on a worker thread; false (nothing started) while one runs.
  bool start(Work work);
  bool running() const { return watcher_.isRunning(); }
  void cancel();
  // Blocks until the running work has finished (the `finished` signal is
  // still delivered through the event loop).
  void wait();

 signals:
  // percent: of the whole job where it is planned (Progress::plan_job),
  // else of its current stage; seconds_left: the whole job's, where known.
  void progressed(int percent, std::optional<double> seconds_left);
  // error: empty on success, "cancelled", or the one-line message of the failure.
  void finished(const QString& error);

 private:
  std::unique_ptr<Progress> progress_;
  QThreadPool pool_;  // one thread, given way (run_giving_way, core/background_work.h)
  QFutureWatcher<QString> watcher_;
  QTimer poll_;
};

}  // namespace relight::gui
