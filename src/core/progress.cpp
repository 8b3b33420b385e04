#include "core/progress.h"

#include <unistd.h>

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

void Progress::draw(bool final_line) {
  if (!show_) return;
  const double f = fraction();
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  constexpr int kWidth = 30;
  const int filled = int(f * kWidth);
  std::string bar(filled, '#');
  bar.resize(kWidth, '.');
  std::fprintf(stderr, "\r%-28s [%s] %3d%% %6.1fs%s", label_.c_str(), bar.c_str(), int(f * 100), secs,
               final_line ? "\n" : "");
  std::fflush(stderr);
}

}  // namespace relight
