// Progress of long work: counts finished units, draws a one-line bar on
// stderr when it is a terminal, and carries a cancel flag that workers poll.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

namespace relight {

// A duration as a person reads it: "12s", "3m10s", "1h06m".
std::string duration_text(double seconds);

// The line drawn for a stage `fraction` (0..1) done after `elapsed_s`
// seconds: label, bar, percentage, the time so far and, once a twentieth is
// done and a second has passed, an estimate of the time left at the pace so
// far ("~12s left", "~3m10s left").
std::string progress_line(const std::string& label, double fraction, double elapsed_s);

// The time left of a job of several stages run one after another (an
// analysis: the lights' direct light, then renders of the bounce light),
// from the time its stages have taken so far. Each planned stage has a kind
// and an amount of work (the paths it traces); stages of one kind take time
// in proportion to their work, so a stage to come is timed at the pace its
// kind went at in this run, or, before any stage of its kind has finished,
// at the running stage's own pace where it is of that kind, else at the
// pace of the stages that have finished. A stage's time runs from its begin
// to the next planned stage's, so the work that follows its bar (filtering,
// dividing) counts with it. Times are seconds on any one clock.
class JobEstimate {
 public:
  struct Stage {
    std::string label;
    int kind = 0;
    double work = 1.0;
  };
  explicit JobEstimate(std::vector<Stage> plan);

  // The stage `label` begins at `t`. The plan's stages are matched in order;
  // planned stages passed over did not run (an iteration that converged
  // early), and a label the plan does not hold is not part of the job.
  void begin(const std::string& label, double t);
  // Seconds left at `t`, the current stage `fraction` done; none before the
  // job is far enough along to tell (a stage done, or a twentieth of the
  // first and a second gone).
  std::optional<double> seconds_left(double fraction, double t) const;
  // The job's share done by time: spent / (spent + left); 0 until known.
  double fraction_done(double fraction, double t) const;

 private:
  // Seconds per unit of work over the finished stages of `kind` (of every
  // kind: -1); none where none has finished.
  std::optional<double> pace(int kind) const;

  std::vector<Stage> plan_;
  std::vector<double> took_;  // seconds each finished stage took (plan order; -1: did not run)
  int current_ = -1;
  double start_ = 0.0, stage_start_ = 0.0;
};

class Progress {
 public:
  // A reporter that shows nothing and is never cancelled.
  static Progress& silent();

  explicit Progress(bool show_on_terminal = true);

  // Starts a stage of `total` units under a short label.
  void begin(const std::string& label, int64_t total);
  // Adds finished units; throws Cancelled if cancel() was called.
  void advance(int64_t units = 1);
  void end();

  void cancel() { cancelled_ = true; }
  bool cancelled() const { return cancelled_; }
  // Fraction of the current stage done, 0..1.
  double fraction() const;

  // The stages of the job to come (JobEstimate): the line then also shows
  // the whole job's time left, and job_fraction() its share done. Until
  // then (and after end_job()) they follow the current stage.
  void plan_job(std::vector<JobEstimate::Stage> stages);
  void end_job();
  double job_fraction() const;
  std::optional<double> job_seconds_left() const;

 private:
  void draw(bool final_line);
  double seconds_since(std::chrono::steady_clock::time_point t) const;

  bool show_;
  std::atomic<bool> cancelled_{false};
  std::atomic<int64_t> done_{0};
  int64_t total_ = 1;
  std::string label_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::mutex draw_mutex_;
  std::optional<JobEstimate> job_;
  std::chrono::steady_clock::time_point job_clock_;
  mutable std::mutex job_mutex_;  // the job is planned on the worker and read by a progress bar's poll
};

}  // namespace relight
