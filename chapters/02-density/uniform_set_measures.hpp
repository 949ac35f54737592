#pragma once
/// \file
/// \brief Numbers a chapter reads off a particle set that is meant to be uniform: the closest
/// pair, the range of the neighbour counts and of h, and the error of the density against one.
///
/// \code
/// const double closest = app::closest_separation(p, box);          // has the set paired up?
/// const app::NeighbourCounts counts = app::neighbour_counts(p);    // after a density pass
/// for (const auto& [name, error] : app::unit_density_errors(p)) ...
/// \endcode

#include "sph/box.hpp"
#include "sph/neighbours.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace app {

/// The smallest distance between two particles of \p p in \p box, found among the neighbours
/// within \f$ 2h \f$ of the particles' own (fixed) smoothing lengths; \f$ 10^{300} \f$ if no
/// particle has a neighbour.
template <int D>
double closest_separation(sph::Particles<D> p, const sph::Box<D>& box) {
  sph::NeighbourSearch<D> search;
  search.update(p, box, sph::SmoothingLengthRule::fixed());
  double closest = 1e300;
  for (std::size_t i = 0; i < p.size(); ++i)
    for (const auto& n : search.list().of(i))
      closest = std::min(closest, search.list().separation(p.position, i, n).norm());
  return closest;
}

/// The smallest, mean and largest neighbour count of a particle set.
struct NeighbourCounts {
  int min = 0;      ///< fewest neighbours of any particle
  int max = 0;      ///< most neighbours of any particle
  double mean = 0;  ///< mean over the particles
};

/// The neighbour counts that the last neighbour search wrote into \p p.
template <int D>
NeighbourCounts neighbour_counts(const sph::Particles<D>& p) {
  NeighbourCounts counts;
  const auto [lo, hi] = std::minmax_element(p.neighbour_count.begin(), p.neighbour_count.end());
  counts.min = *lo;
  counts.max = *hi;
  for (int c : p.neighbour_count) counts.mean += c / static_cast<double>(p.size());
  return counts;
}

/// The ratio of the largest to the smallest smoothing length of \p p (1 for a constant h).
template <int D>
double smoothing_length_spread(const sph::Particles<D>& p) {
  const auto [lo, hi] = std::minmax_element(p.smoothing_length.begin(), p.smoothing_length.end());
  return *hi / *lo;
}

/// The two errors of a set whose intended density is one everywhere: "rms error", the
/// root-mean-square of \f$ \rho_i - 1 \f$ over the particles, and "|mean error|", the bias of
/// the mean \f$ |\bar\rho - 1| \f$ -- in the form an sph::ErrorVsTime record takes them.
template <int D>
std::vector<std::pair<std::string, double>> unit_density_errors(const sph::Particles<D>& p) {
  double square = 0, mean = 0;
  for (double rho : p.density) {
    square += (rho - 1.0) * (rho - 1.0) / static_cast<double>(p.size());
    mean += rho / static_cast<double>(p.size());
  }
  return {{"rms error", std::sqrt(square)}, {"|mean error|", std::abs(mean - 1.0)}};
}

}  // namespace app
