#include "progress_bar.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include <fmt/format.h>

namespace servoloop::cli {

ProgressBar::ProgressBar(double total_s) : total_s_(total_s), enabled_(::isatty(STDERR_FILENO) == 1) {}

ProgressBar::~ProgressBar() { finish(); }

std::string ProgressBar::render(double sim_time_s, double total_s, double wall_time_s, int width) {
  const double fraction = total_s > 0.0 ? std::clamp(sim_time_s / total_s, 0.0, 1.0) : 1.0;
  const int filled = static_cast<int>(fraction * width + 0.5);
  std::string bar = "[" + std::string(filled, '#') + std::string(width - filled, '.') + "]";
  const double rtf = wall_time_s > 0.0 ? sim_time_s / wall_time_s : 0.0;
  return fmt::format("{} {:6.1f} / {:.1f} s simulated  (RTF {:.3g})", bar, sim_time_s, total_s, rtf);
}

void ProgressBar::update(double sim_time_s, double wall_time_s) {
  if (!enabled_) return;
  // \r and "erase to end of line": the bar overwrites itself.
  std::fprintf(stderr, "\r%s\x1b[K", render(sim_time_s, total_s_, wall_time_s, 30).c_str());
  std::fflush(stderr);
  drawn_ = true;
}

void ProgressBar::finish() {
  if (!enabled_ || !drawn_) return;
  std::fprintf(stderr, "\r\x1b[K");
  std::fflush(stderr);
  drawn_ = false;
}

}  // namespace servoloop::cli
