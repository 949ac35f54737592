#include "app/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>
#include <utility>

namespace app {

ProgressDisplay ProgressDisplay::automatic() {
  ProgressDisplay display;
  display.live = isatty(STDERR_FILENO) ? &std::cerr : nullptr;
  display.report = &std::cout;
  return display;
}

Progress::Progress(double t_end, std::string label)
    : Progress(t_end, std::move(label), ProgressDisplay::automatic()) {}

Progress::Progress(double t_end, std::string label, ProgressDisplay display)
    : t_end_(t_end), label_(std::move(label)), display_(display) {}

Progress::~Progress() { clear_live_line(); }

void Progress::update(long step, double t, double dt) {
  steps_ = step + 1;
  t_ = t;
  dt_ = dt;
  const double now = clock_.seconds();
  if (!have_first_) {
    have_first_ = true;
    t_first_ = t;
    seconds_first_ = now;
  }
  if (display_.live == nullptr || now < display_.delay_seconds ||
      (last_draw_ >= 0.0 && now - last_draw_ < display_.refresh_seconds)) {
    return;
  }
  last_draw_ = now;
  // \r returns to the start of the line, ESC[K clears what is left of a longer earlier line.
  *display_.live << '\r' << status_line() << "\033[K" << std::flush;
  line_shown_ = true;
}

std::string Progress::status_line() const {
  std::ostringstream line;
  line.precision(4);
  line << label_ << ": step " << steps_ << "  t = " << t_ << " / " << t_end_;
  line.precision(3);
  line << "  dt = " << dt_;
  // The estimate assumes the remaining simulated time costs as much per unit as the past.
  const double done = t_ - t_first_;
  const double span = t_end_ - t_first_;
  if (have_first_ && done > 0.0 && span > 0.0) {
    const double percent = std::min(100.0, 100.0 * done / span);
    const double elapsed = clock_.seconds() - seconds_first_;
    const double left = std::max(0.0, (t_end_ - t_) * elapsed / done);
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "  %3.0f%%  ETA %s", percent,
                  format_duration(left).c_str());
    line << buffer;
  }
  return line.str();
}

void Progress::clear_live_line() {
  if (line_shown_ && display_.live != nullptr) {
    *display_.live << "\r\033[K" << std::flush;
  }
  line_shown_ = false;
}

void Progress::finish() {
  if (finished_) return;
  finished_ = true;
  clear_live_line();
  if (display_.report != nullptr) {
    std::ostringstream report;
    report.precision(6);
    report << label_ << ": " << steps_ << (steps_ == 1 ? " step" : " steps") << " to t = " << t_
           << " in " << format_duration(clock_.seconds()) << '\n';
    *display_.report << report.str() << std::flush;
  }
}

std::string format_duration(double seconds) {
  char buffer[64];
  if (!std::isfinite(seconds)) {
    return "?";
  }
  if (seconds < 10.0) {
    std::snprintf(buffer, sizeof buffer, "%.2f s", seconds);
  } else if (seconds < 60.0) {
    std::snprintf(buffer, sizeof buffer, "%.1f s", seconds);
  } else if (seconds < 3600.0) {
    const long whole = std::lround(seconds);
    std::snprintf(buffer, sizeof buffer, "%ld min %02ld s", whole / 60, whole % 60);
  } else {
    const long minutes = std::lround(seconds / 60.0);
    std::snprintf(buffer, sizeof buffer, "%ld h %02ld min", minutes / 60, minutes % 60);
  }
  return buffer;
}

}  // namespace app
