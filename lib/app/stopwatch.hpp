#pragma once
/// \file
/// \brief app::Stopwatch: wall-clock time of a run or a part of it.

#include <chrono>

namespace app {

/// Measures wall-clock time from its construction (or the last restart()).
///
/// \code
/// app::Stopwatch clock;
/// run_the_scene();
/// std::printf("run time %.2f s\n", clock.seconds());
/// \endcode
class Stopwatch {
 public:
  /// Starts the clock.
  Stopwatch() : start_(Clock::now()) {}

  /// Seconds since construction or the last restart().
  [[nodiscard]] double seconds() const {
    return std::chrono::duration<double>(Clock::now() - start_).count();
  }

  /// Starts again from zero and returns the seconds measured until now.
  double restart() {
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    start_ = now;
    return elapsed;
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_;
};

}  // namespace app
