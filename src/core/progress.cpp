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

namespace {

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

}  // namespace

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
  // Padded so that a shorter line wipes the "left" of the one before.
  std::fprintf(stderr, "\r%-90s%s", progress_line(label_, fraction(), secs).c_str(), final_line ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace relight
