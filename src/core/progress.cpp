#include "core/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/error.h"

namespace relight {

Progress& Progress::silent() {
  static Progress p(false);
  return p;
}

Progress::Progress(bool show_on_terminal) : show_(show_on_terminal && isatty(STDERR_FILENO)) {}

void Progress::begin(const std::string& label, int64_t total) {
  label_ = label;
  total_ = total > 0 ? total : 1;
  done_ = 0;
  start_ = last_draw_ = std::chrono::steady_clock::now();
  {
    const std::lock_guard lock(job_mutex_);
    if (job_) job_->begin(label, seconds_since(job_clock_));
  }
  if (cancelled_) throw Cancelled();
  draw(false);
}

void Progress::advance(int64_t units) {
  done_ += units;
  if (cancelled_) throw Cancelled();
  if (!show_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_draw_ < std::chrono::milliseconds(200)) return;
  std::unique_lock lock(draw_mutex_, std::try_to_lock);
  if (!lock.owns_lock()) return;
  last_draw_ = now;
  draw(false);
}

void Progress::end() {
  done_ = total_;
  draw(true);
}

double Progress::fraction() const { return double(done_) / double(total_); }

double Progress::seconds_since(std::chrono::steady_clock::time_point t) const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

void Progress::plan_job(std::vector<JobEstimate::Stage> stages) {
  const std::lock_guard lock(job_mutex_);
  job_.emplace(std::move(stages));
  job_clock_ = std::chrono::steady_clock::now();
}

void Progress::end_job() {
  const std::lock_guard lock(job_mutex_);
  job_.reset();
}

double Progress::job_fraction() const {
  const std::lock_guard lock(job_mutex_);
  return job_ ? job_->fraction_done(fraction(), seconds_since(job_clock_)) : fraction();
}

std::optional<double> Progress::job_seconds_left() const {
  const std::lock_guard lock(job_mutex_);
  if (!job_) return std::nullopt;
  return job_->seconds_left(fraction(), seconds_since(job_clock_));
}

JobEstimate::JobEstimate(std::vector<Stage> plan) : plan_(std::move(plan)) {}

void JobEstimate::begin(const std::string& label, double t) {
  int next = current_ + 1;
  while (next < int(plan_.size()) && plan_[size_t(next)].label != label) ++next;
  if (next >= int(plan_.size())) return;
  if (current_ < 0) start_ = t;
  if (current_ >= 0) took_.push_back(t - stage_start_);
  took_.resize(size_t(next), -1.0);  // stages passed over
  current_ = next;
  stage_start_ = t;
}

std::optional<double> JobEstimate::pace(int kind) const {
  double seconds = 0.0, work = 0.0;
  for (size_t i = 0; i < took_.size(); ++i)
    if (took_[i] >= 0.0 && (kind < 0 || plan_[i].kind == kind)) {
      seconds += took_[i];
      work += plan_[i].work;
    }
  if (work <= 0.0) return std::nullopt;
  return seconds / work;
}

std::optional<double> JobEstimate::seconds_left(double fraction, double t) const {
  if (current_ < 0) return std::nullopt;
  const Stage& stage = plan_[size_t(current_)];
  const double in_stage = t - stage_start_, f = std::clamp(fraction, 0.0, 1.0);
  // The current stage's own pace sees its bar only, its kind's the whole
  // span; the longer of the two.
  std::optional<double> own_pace;  // seconds per unit of work
  if (f >= 0.05 && in_stage >= 1.0) own_pace = in_stage / (f * stage.work);
  const auto any_pace = pace(-1);
  auto kind_pace = pace(stage.kind);
  if (!kind_pace && !own_pace) kind_pace = any_pace;
  if (!own_pace && !kind_pace) return std::nullopt;
  double left = std::max(own_pace ? *own_pace * stage.work * (1.0 - f) : 0.0,
                         kind_pace ? *kind_pace * stage.work - in_stage : 0.0);
  // A stage to come whose kind has not finished a stage goes at the current
  // stage's own pace where it is of that kind (its first render shows what
  // the plan's weights got wrong), else at the pace of all that has run.
  for (size_t i = size_t(current_) + 1; i < plan_.size(); ++i) {
    auto p = pace(plan_[i].kind);
    if (!p) p = plan_[i].kind == stage.kind && own_pace ? own_pace : any_pace ? any_pace : own_pace;
    left += *p * plan_[i].work;
  }
  return left;
}

double JobEstimate::fraction_done(double fraction, double t) const {
  const auto left = seconds_left(fraction, t);
  if (!left) return 0.0;
  const double spent = t - start_;
  return spent + *left > 0.0 ? spent / (spent + *left) : 1.0;
}

std::string duration_text(double seconds) {
  const int s = int(std::lround(seconds));
  char text[32];
  if (s < 60)
    std::snprintf(text, sizeof text, "%ds", s);
  else if (s < 3600)
    std::snprintf(text, sizeof text, "%dm%02ds", s / 60, s % 60);
  else
    std::snprintf(text, sizeof text, "%dh%02dm", s / 3600, s / 60 % 60);
  return text;
}

std::string progress_line(const std::string& label, double fraction, double elapsed_s) {
  constexpr int kWidth = 30;
  const double f = std::clamp(fraction, 0.0, 1.0);
  std::string bar(size_t(f * kWidth), '#');
  bar.resize(kWidth, '.');
  std::string left;
  if (f >= 0.05 && f < 1.0 && elapsed_s >= 1.0) left = "  ~" + duration_text(elapsed_s * (1.0 - f) / f) + " left";
  char line[256];
  std::snprintf(line, sizeof line, "%-28s [%s] %3d%% %6.1fs%s", label.c_str(), bar.c_str(), int(f * 100), elapsed_s,
                left.c_str());
  return line;
}

void Progress::draw(bool final_line) {
  if (!show_) return;
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  std::string line = progress_line(label_, fraction(), secs);
  if (const auto left = job_seconds_left(); left && !final_line) line += "  (all: ~" + duration_text(*left) + " left)";
  // Padded so that a shorter line wipes the "left" of the one before.
  std::fprintf(stderr, "\r%-110s%s", line.c_str(), final_line ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace relight
