#pragma once
/// \file
/// \brief Reading numbers off recorded series: the value at a time, linear interpolation in a
/// table, and a percentile of a list.
///
/// A chapter records a run as series (times and energies, radii and densities) and then reads
/// single numbers off them for its tables and checks:
///
/// \code
/// std::printf("%.4f\n", app::value_at(t, kinetic, 0.8));    // the first record at t >= 0.8
/// const double rho = app::interpolate(ref_r, ref_rho, 0.14);  // a reference profile at r
/// const double p99 = app::percentile(errors, 0.99);
/// \endcode

#include <algorithm>
#include <cstddef>
#include <vector>

namespace app {

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
