// Progress of long work: counts finished units, draws a one-line bar on
// stderr when it is a terminal, and carries a cancel flag that workers poll.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <mutex>
#include <string>

namespace relight {

// The line drawn for a stage `fraction` (0..1) done after `elapsed_s`
// seconds: label, bar, percentage, the time so far and, once a twentieth is
// done and a second has passed, an estimate of the time left at the pace so
// far ("~12s left", "~3m10s left").
std::string progress_line(const std::string& label, double fraction, double elapsed_s);

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

 private:
  void draw(bool final_line);

  bool show_;
  std::atomic<bool> cancelled_{false};
  std::atomic<int64_t> done_{0};
  int64_t total_ = 1;
  std::string label_;
  std::chrono::steady_clock::time_point start_, last_draw_;
  std::mutex draw_mutex_;
};

}  // namespace relight
