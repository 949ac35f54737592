#pragma once
/// \file
/// \brief The density step timed: one neighbour search with fixed h and one density pass, its
/// wall-clock time, and a study that records the density error of uniform sets -- lattices and
/// glasses in the periodic unit box -- against that time.
///
/// \code
/// const double seconds = app::timed_density_step(p, box, sph::DensityForm::watkins());
///
/// app::DensityCostStudy cost{sph::ErrorVsTime("density error against time")};
/// {
///   const app::SingleThread one_thread;   // times that compare across N
///   app::record_density_run(cost, "lattice, 64 neighbours", p, box);
/// }
/// std::printf("%s", cost.study.table().c_str());
/// \endcode
///
/// The errors recorded are those of app::unit_density_errors (in uniform_set_measures.hpp,
/// shown in Step 3): the set's intended density is one everywhere.

#include "uniform_set_measures.hpp"
#include "app/stopwatch.hpp"
#include "app/text.hpp"
#include "sph/box.hpp"
#include "sph/density.hpp"
#include "sph/measures/convergence.hpp"
#include "sph/neighbours.hpp"
#include "sph/particles.hpp"
#include "sph/setups/relax.hpp"
#include "sph/setups/watkins_static.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace app {

/// Runs the density step on \p p in \p box -- the neighbour search with the particles' fixed
/// h, then the density sum of \p form -- and returns its wall-clock seconds.
template <int D>
double timed_density_step(sph::Particles<D>& p, const sph::Box<D>& box, sph::DensityForm form) {
  const Stopwatch clock;
  sph::NeighbourSearch<D> search;
  search.update(p, box, sph::SmoothingLengthRule::fixed());
  sph::compute_density(p, search.list(), form);
  return clock.seconds();
}

/// While it exists, OpenMP runs on one thread: its constructor remembers the number of threads
/// and sets it to one, and its destructor restores the number it remembered.
class SingleThread {
 public:
  SingleThread() : threads_(omp_get_max_threads()) { omp_set_num_threads(1); }
  ~SingleThread() { omp_set_num_threads(threads_); }
  SingleThread(const SingleThread&) = delete;             ///< not copied
  SingleThread& operator=(const SingleThread&) = delete;  ///< not assigned

 private:
  int threads_;
};

/// The runs of a density-cost study, and what building its glasses cost besides.
struct DensityCostStudy {
  sph::ErrorVsTime study;      ///< one record per set: its errors and the time of its step
  double relax_seconds = 0;    ///< time spent relaxing glasses, not in the study's times
  long relaxed_particles = 0;  ///< particles relaxed in all
};

/// Times the density step of \p p in \p box (gather with self term, the best of three runs,
/// since the machine may be shared), records the set's errors against that time as a run of
/// \p method in \p cost, and prints one line: N, the time, and the two errors.
template <int D>
void record_density_run(DensityCostStudy& cost, const std::string& method, sph::Particles<D>& p,
                        const sph::Box<D>& box) {
  double seconds = 1e300;
  for (int k = 0; k < 3; ++k)
    seconds = std::min(seconds, timed_density_step(p, box, sph::DensityForm::watkins()));
  const int n = static_cast<int>(p.size());
  cost.study.add({method, n, sph::root<D>(1.0 / n), seconds, unit_density_errors(p)});
  std::printf("  %s: N = %d, %.4f s, rms error %.3e, |mean error| %.3e\n", method.c_str(), n,
              seconds, cost.study.records().back().error("rms error"),
              cost.study.records().back().error("|mean error|"));
}

/// The sweep of a density-cost study in the periodic unit box, on one thread so that the times
/// compare across N: for each neighbour number of \p neighbour_numbers (Watkins' constant h,
/// sph::setups::unit_box_particles), the cubic lattices of the sides \p lattice_sides and the
/// glasses of the sides \p glass_sides, recorded as "lattice, 64 neighbours" and
/// "glass, 64 neighbours".  A glass is a random set (seed 1000 + side) relaxed to uniform
/// density before its density step is timed; the relaxation's time goes to
/// DensityCostStudy::relax_seconds.
inline void run_density_cost_sweep(DensityCostStudy& cost,
                                   const std::vector<double>& neighbour_numbers,
                                   const std::vector<int>& lattice_sides,
                                   const std::vector<int>& glass_sides) {
  using sph::setups::unit_box;
  const SingleThread one_thread;
  for (double neighbours : neighbour_numbers) {
    const std::string label = format("%.0f", neighbours) + " neighbours";
    for (int side : lattice_sides) {
      const std::array<int, 3> cells{side, side, side};
      auto p = sph::setups::unit_box_particles<3>(
          sph::lattice<3>(sph::LatticeType::cubic, sph::Vec<3>::Zero(), sph::Vec<3>::Ones(), cells),
          neighbours);
      record_density_run(cost, "lattice, " + label, p, unit_box<3>());
    }
    for (int side : glass_sides) {
      // The glass is built first, outside the timed density step.
      const std::size_t n = static_cast<std::size_t>(side) * side * side;
      auto p = sph::setups::watkins_random_set<3>(n, neighbours, 1000 + side);
      const Stopwatch relax_clock;
      sph::relax_to_uniform_density(p, unit_box<3>());
      cost.relax_seconds += relax_clock.seconds();
      cost.relaxed_particles += static_cast<long>(n);
      record_density_run(cost, "glass, " + label, p, unit_box<3>());
    }
  }
}

}  // namespace app
