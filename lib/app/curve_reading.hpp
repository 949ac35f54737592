#pragma once
/// \file
/// \brief Reading numbers off sampled curves and recorded series: where a profile first crosses
/// a level, a curve's value at a given time on log-log axes (between measured points, or along a
/// power law through two of them), the value of a series at a time, linear interpolation in a
/// table, and a percentile of a list.
///
/// A chapter that compares runs reads single numbers off their curves: the position of a front
/// in a profile, an error at a run time no run had exactly.  These are the interpolations it
/// uses:
///
/// \code
/// // (x, P) samples sorted by x: the shock, scanned from the right, at P = 0.2016
/// const double shock = app::first_crossing(pressure, 0.2016, true);
/// // (seconds, error) points: the error at 0.5 s, log-log between the neighbouring runs
/// bool outside = false;
/// const double error = app::loglog_at(points, 0.5, outside);
/// // a power law through two quoted points, read at 0.5 s
/// const double quoted = app::power_law_at(0.18, 2.17e-3, 2.12, 5.4e-4, 0.5);
/// // a recorded series at a time, a reference profile at a radius, a percentile
/// std::printf("%.4f\n", app::value_at(t, kinetic, 0.8));    // the first record at t >= 0.8
/// const double rho = app::interpolate(ref_r, ref_rho, 0.14);
/// const double p99 = app::percentile(errors, 0.99);
/// \endcode

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace app {

/// Where a sampled function first crosses \p level when its samples, (x, f) pairs sorted by x,
/// are scanned from one end inwards: from the left end, or from the right end when
/// \p from_right.  The crossing is interpolated linearly between the two samples that bracket
/// it; a pair of samples with equal values is skipped (it cannot place a crossing).  NaN when f
/// never reaches the level, so that a comparison with a missing front fails instead of passing
/// by accident.
inline double first_crossing(const std::vector<std::pair<double, double>>& samples, double level,
                             bool from_right) {
  const std::size_t n = samples.size();
  for (std::size_t k = 1; k < n; ++k) {
    const auto& [x_out, f_out] = samples[from_right ? n - k : k - 1];  // the sample outside
    const auto& [x_in, f_in] = samples[from_right ? n - k - 1 : k];    // the next one inwards
    if ((f_out - level) * (f_in - level) <= 0 && f_in != f_out) {
      return x_out + (level - f_out) / (f_in - f_out) * (x_in - x_out);
    }
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// The power law \f$ e(t) = e_0 (e_1/e_0)^{\ln(t/t_0)/\ln(t_1/t_0)} \f$ through the two points
/// \f$ (t_0, e_0) \f$ and \f$ (t_1, e_1) \f$, read at \p t: the straight line through them on
/// log-log axes, which is all that two measurements say about a curve.
inline double power_law_at(double t0, double e0, double t1, double e1, double t) {
  return e0 * std::pow(e1 / e0, std::log(t / t0) / std::log(t1 / t0));
}

/// The value of a curve of (time, value) points, in any order and at least two, at the time
/// \p t: interpolated linearly in \f$ \ln t \f$ and \f$ \ln \f$ value between the two points
/// that bracket \p t, or extrapolated along the first or last segment when \p t lies outside
/// the points' span, which \p outside then reports.  Times and values must be positive.
inline double loglog_at(std::vector<std::pair<double, double>> points, double t, bool& outside) {
  std::sort(points.begin(), points.end());
  outside = t < points.front().first || t > points.back().first;
  std::size_t k = 1;
  while (k + 1 < points.size() && points[k].first < t) ++k;
  const auto& [t0, e0] = points[k - 1];
  const auto& [t1, e1] = points[k];
  return power_law_at(t0, e0, t1, e1, t);
}

/// The value of a recorded series at the first record at or after \p when: \p t holds the
/// record times (increasing), \p values one value per time.  Past the last record, the last
/// value.
inline double value_at(const std::vector<double>& t, const std::vector<double>& values,
                       double when) {
  const auto k = static_cast<std::size_t>(std::lower_bound(t.begin(), t.end(), when) - t.begin());
  return values[std::min(k, values.size() - 1)];
}

/// Linear interpolation in a table \p x (increasing) -> \p y at \p at; the end values beyond
/// the table.
inline double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  const auto k = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), at) - x.begin());
  const double w = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return (1 - w) * y[k - 1] + w * y[k];
}

/// The \p p-th quantile of \p values, p in [0, 1] (0.5: the median, 0.99: the 99th
/// percentile), as the nearest entry of the sorted list; \p values must not be empty.
inline double percentile(std::vector<double> values, double p) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(p * double(values.size() - 1) + 0.5)];
}

}  // namespace app
