#include "gui/background_task.h"

#include <QtConcurrent/QtConcurrentRun>

#include "core/background_work.h"
#include "core/error.h"

namespace relight::gui {

BackgroundTask::BackgroundTask(QObject* parent) : QObject(parent) {
  pool_.setMaxThreadCount(1);
  poll_.setInterval(100);
  connect(&poll_, &QTimer::timeout, this,
          [this] { emit progressed(int(100.0 * progress_->job_fraction() + 0.5), progress_->job_seconds_left()); });
  connect(&watcher_, &QFutureWatcher<QString>::finished, this, [this] {
    poll_.stop();
    emit finished(watcher_.result());
  });
}

BackgroundTask::~BackgroundTask() {
  cancel();
  watcher_.waitForFinished();
}

bool BackgroundTask::start(Work work) {
  if (running()) return false;
  progress_ = std::make_unique<Progress>(false);
  Progress* progress = progress_.get();
  watcher_.setFuture(QtConcurrent::run(&pool_, [work = std::move(work), progress]() -> QString {
    try {
      run_giving_way([&] { work(*progress); });
      return {};
    } catch (const Cancelled&) {
      return QStringLiteral("cancelled");
    } catch (const std::exception& e) {
      return QString::fromStdString(e.what());
    }
  }));
  poll_.start();
  return true;
}

void BackgroundTask::cancel() {
  if (running()) progress_->cancel();
}

void BackgroundTask::wait() { watcher_.waitForFinished(); }

}  // namespace relight::gui
