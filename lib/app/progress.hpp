#pragma once
/// \file
/// \brief app::Progress: one updating status line for long time integrations.

#include <iosfwd>
#include <string>

#include "app/stopwatch.hpp"

namespace app {

/// Where and how a Progress reports.
struct ProgressDisplay {
  /// Stream for the live status line (normally std::cerr); nullptr shows none.
  std::ostream* live = nullptr;
  /// Stream for the final report (normally std::cout); nullptr prints none.
  std::ostream* report = nullptr;
  /// The live line appears only once the run has lasted this many seconds.
  double delay_seconds = 2.0;
  /// The live line is redrawn at most this often (seconds).
  double refresh_seconds = 0.2;

  /// The default: a live line on std::cerr if standard error is a terminal, otherwise none
  /// (CI logs and captured output stay clean); the final report on std::cout.
  static ProgressDisplay automatic();
};

/// Reports the progress of a time integration from t = 0 (or the first update) to t_end.
///
/// On a terminal, a run longer than a couple of seconds shows one line on standard error that
/// is redrawn in place: step, time, time step, percentage and the estimated time left.  Off a
/// terminal nothing is shown until finish(), which prints a one-line report to standard output:
///
/// \code
/// app::Progress progress(t_end, "Sod 1D");
/// for (long step = 0; t < t_end; ++step) {
///   dt = advance(state);  t += dt;
///   progress.update(step, t, dt);
/// }
/// progress.finish();   // "Sod 1D: 812 steps to t = 0.2 in 3.41 s"
/// \endcode
class Progress {
 public:
  /// A progress report for a run ending at time \p t_end, labelled \p label, shown according to
  /// ProgressDisplay::automatic().
  Progress(double t_end, std::string label);
  /// The same with an explicit display (tests, or a report to a different stream).
  Progress(double t_end, std::string label, ProgressDisplay display);
  /// Clears the live line if finish() was not called.
  ~Progress();

  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Records that step number \p step has reached time \p t with time step \p dt; redraws the
  /// live line when it is due.  Cheap enough to call every step.
  void update(long step, double t, double dt);

  /// Clears the live line and prints the final report: steps, final time, wall time.
  void finish();

  /// Wall-clock seconds since construction.
  [[nodiscard]] double seconds() const { return clock_.seconds(); }
  /// Number of the last step passed to update() plus one (the number of steps taken).
  [[nodiscard]] long steps() const { return steps_; }
  /// The status line as it would be drawn now (without control characters).
  [[nodiscard]] std::string status_line() const;

 private:
  void clear_live_line();

  double t_end_;
  std::string label_;
  ProgressDisplay display_;
  Stopwatch clock_;
  long steps_ = 0;
  double t_ = 0.0;
  double dt_ = 0.0;
  double t_first_ = 0.0;
  double seconds_first_ = 0.0;
  bool have_first_ = false;
  double last_draw_ = -1.0;
  bool line_shown_ = false;
  bool finished_ = false;
};

/// Formats a duration in seconds for people: "0.42 s", "12.3 s", "4 min 05 s", "2 h 03 min".
std::string format_duration(double seconds);

}  // namespace app
