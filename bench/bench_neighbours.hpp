#pragma once
// The cost of the first pass of every step: 10^5 particles in a periodic unit cube (3D), placed
// uniformly at random, 64 neighbours.  Timed separately:
//   grid build      counting sort into cells (CellGrid::build, the cell size the search uses)
//   search, cold    smoothing lengths from nothing + neighbour list (the first step of a run)
//   search, warm    the same with last step's h (the common case: most h stay in tolerance)
//   density rule    h from the density (Newton, Watkins eq A6) + list, warm, then the density pass
//   density pass    compute_density alone on the finished list
//   reuse           the next update of the same search with the particles unmoved (no grid)
// Each with 1 thread and with all threads, best of a few repetitions; reported as microseconds
// per particle and nanoseconds per neighbour pair (an (i, j) list entry; each pair appears from
// both sides, as the gather passes visit it).  The last column says whether the list and the
// densities of the two thread counts agree bitwise.

#include "sph/density.hpp"
#include "sph/setups/initial_conditions.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <functional>
#include <string>

namespace bench {

namespace neighbours_detail {

// Best wall time of `repeats` calls of `prepare(); work();` (only `work` is timed).
inline double best_seconds(int repeats, const std::function<void()>& prepare,
                           const std::function<void()>& work) {
  double best = 1e300;
  for (int k = 0; k < repeats; ++k) {
    prepare();
    const auto start = std::chrono::steady_clock::now();
    work();
    best = std::min(
        best, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }
  return best;
}

struct Timings {
  double grid = 0, cold = 0, warm = 0, reuse = 0, density_rule = 0, density_pass = 0;  // seconds
  double entries = 0;          // list entries
  std::vector<double> h, rho;  // for the bitwise check
};

// Time every stage with `threads` threads on a copy of `start`.
inline Timings time_stages(const sph::Particles<3>& start, const sph::Box<3>& box,
                           double neighbours, int threads, int repeats) {
  omp_set_num_threads(threads);
  Timings t;
  sph::Particles<3> p = start;
  sph::NeighbourSearch<3> search;
  const auto count_rule = sph::SmoothingLengthRule::neighbour_number(neighbours, 0.05 * neighbours);
  const auto density_rule = sph::SmoothingLengthRule::from_density(neighbours);
  // Cold search: no smoothing lengths yet.  Every timed search is a full one (a search that has
  // searched before would otherwise reuse its candidates, timed separately as "reuse").
  search.update(p, box, count_rule);  // first touch of the buffers, not timed
  t.cold = best_seconds(
      repeats,
      [&] {
        std::fill(p.smoothing_length.begin(), p.smoothing_length.end(), 0.0);
        search.forget_candidates();
      },
      [&] { search.update(p, box, count_rule); });
  // Grid build alone, with the cell size the search chooses (half the search radius in 3D).
  std::vector<double> h = p.smoothing_length;
  std::nth_element(h.begin(), h.begin() + static_cast<std::ptrdiff_t>(h.size() / 2), h.end());
  const double cell = 0.5 * 2.0 * h[h.size() / 2] * (1.0 + search.search_margin);
  sph::CellGrid<3> grid;
  t.grid = best_seconds(
      repeats, [] {}, [&] { grid.build(p.position, box, cell); });
  // Warm search: h from the previous call, within tolerance; a full search all the same.
  t.warm = best_seconds(
      repeats, [&] { search.forget_candidates(); }, [&] { search.update(p, box, count_rule); });
  // Reuse: the same search again, particles unmoved (the cost of a step that reuses).
  t.reuse = best_seconds(
      repeats, [] {}, [&] { search.update(p, box, count_rule); });
  t.entries = static_cast<double>(search.list().entries());
  // Density rule (warm: start from its own previous h, full search), then the density pass.
  search.update(p, box, density_rule);
  t.density_rule = best_seconds(
      repeats, [&] { search.forget_candidates(); },
      [&] {
        search.update(p, box, density_rule);
        sph::compute_density(p, search.list(), sph::DensityForm::watkins());
      });
  t.density_pass = best_seconds(
      repeats, [] {}, [&] { sph::compute_density(p, search.list(), sph::DensityForm::watkins()); });
  t.h = p.smoothing_length;
  t.rho = p.density;
  return t;
}

}  // namespace neighbours_detail

/// Print the neighbour-search table (1 thread and all threads).
inline void bench_neighbours(bool quick) {
  using neighbours_detail::Timings;
  const std::size_t n = quick ? 10000 : 100000;
  const double neighbours = 64;
  const int repeats = quick ? 2 : 3;
  const int threads = omp_get_num_procs();
  const auto box = sph::Box<3>::periodic_box(sph::Vec<3>::Zero(), sph::Vec<3>::Ones());
  const auto start =
      sph::make_particles<3>(sph::uniform_random<3>(sph::Vec<3>::Zero(), sph::Vec<3>::Ones(), n, 1),
                             1.0 / static_cast<double>(n));
  const Timings one = neighbours_detail::time_stages(start, box, neighbours, 1, repeats);
  const Timings all = neighbours_detail::time_stages(start, box, neighbours, threads, repeats);
  omp_set_num_threads(threads);

  const double per_particle = 1e6 / static_cast<double>(n), per_pair = 1e9 / one.entries;
  std::printf(
      "\nNeighbour search, 3D periodic unit cube, %zu random particles, %g neighbours "
      "(%.1f list entries per particle), best of %d\n",
      n, neighbours, one.entries / static_cast<double>(n), repeats);
  std::printf("%-34s %10s %10s %9s %9s\n", "stage", "us/part", "us/part", "ns/pair", "ns/pair");
  std::printf("%-34s %10s %10s %9s %9s\n", "", "1 thread",
              (std::to_string(threads) + " thr").c_str(), "1 thread",
              (std::to_string(threads) + " thr").c_str());
  auto row = [&](const char* stage, double a, double b) {
    std::printf("%-34s %10.3f %10.3f %9.2f %9.2f\n", stage, a * per_particle, b * per_particle,
                a * per_pair, b * per_pair);
  };
  row("grid build", one.grid, all.grid);
  row("search, cold (h from nothing)", one.cold, all.cold);
  row("search, warm (N +- 5 %)", one.warm, all.warm);
  row("reuse of the candidates (unmoved)", one.reuse, all.reuse);
  row("density rule + density, warm", one.density_rule, all.density_rule);
  row("density pass alone", one.density_pass, all.density_pass);
  std::printf("h and density identical for 1 and %d threads: %s\n", threads,
              one.h == all.h && one.rho == all.rho ? "yes" : "NO");
}

}  // namespace bench
