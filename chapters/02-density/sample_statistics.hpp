#pragma once
/// \file
/// \brief app::sample_statistics: the mean of repeated measurements and their spread.
///
/// A measurement on a random particle set is one draw.  To judge a number quoted from a paper
/// a chapter repeats the draw and reports the mean over the draws and their spread, the sample
/// standard deviation (with the \f$ n - 1 \f$ of an unbiased variance):
///
/// \code
/// std::vector<double> sigmas;   // one per draw
/// const app::SampleStatistics s = app::sample_statistics(sigmas);
/// std::printf("%.4f +- %.4f\n", s.mean, s.spread);
/// \endcode

#include <cmath>
#include <vector>

namespace app {

/// The mean of a sample and its standard deviation.
struct SampleStatistics {
  double mean = 0;    ///< \f$ \bar x = \frac1n \sum_k x_k \f$
  double spread = 0;  ///< \f$ \big(\frac{1}{n-1} \sum_k (x_k - \bar x)^2\big)^{1/2} \f$
};

/// The mean and spread of \p values (at least two, for the spread to be defined).
inline SampleStatistics sample_statistics(const std::vector<double>& values) {
  SampleStatistics s;
  for (double v : values) s.mean += v / static_cast<double>(values.size());
  for (double v : values)
    s.spread += (v - s.mean) * (v - s.mean) / static_cast<double>(values.size() - 1);
  s.spread = std::sqrt(s.spread);
  return s;
}

}  // namespace app
