#pragma once
// The cost of self-gravity: the Barnes-Hut tree (sph/gravity/tree.hpp, default theta 0.3 with
// quadrupoles, leaves of 16, groups of 32) on a uniform sphere and on the 1/r profile of the
// Evrard collapse, at 8192, 22000 and 65536 particles; direct summation at 8192 for comparison.
// Each evaluation is timed whole, the repeats alternate between the two profiles, and the
// medians are quoted.  Reported per evaluation: the build (sorting into the tree, the nodes'
// moments) and the walk (the lists and the sums over them) in milliseconds, microseconds per
// particle with all threads and with 1, nanoseconds per interaction (all threads), and the
// particle-particle and particle-node interactions per particle.

#include "sph/gravity/direct.hpp"
#include "sph/gravity/tree.hpp"
#include "sph/setups/initial_conditions.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

namespace bench {

namespace gravity_detail {

// The random ball of the library: uniform, or 1/r with `cusp`; h for 64 neighbours.
inline sph::Particles<3> sphere(std::size_t n, bool cusp, std::uint64_t seed) {
  return sph::random_ball(n, seed, cusp);
}

inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

// One evaluation of `gravity` on a copy of p, timed (wall clock, seconds).
template <class Gravity>
double time_evaluation(Gravity& gravity, const sph::Particles<3>& p) {
  sph::Particles<3> q = p;
  const auto start = std::chrono::steady_clock::now();
  gravity.add_accelerations(q, sph::Box<3>::open());
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

struct Measured {
  std::vector<double> total, build, walk, serial;
  double particle_interactions = 0, node_interactions = 0;
};

}  // namespace gravity_detail

inline void bench_gravity(bool quick) {
  using namespace gravity_detail;
  const int threads = omp_get_num_procs();
  const int repeats = quick ? 3 : 7;
  const std::vector<std::size_t> sizes =
      quick ? std::vector<std::size_t>{2048, 8192} : std::vector<std::size_t>{8192, 22000, 65536};
  std::printf(
      "\nSelf-gravity, Barnes-Hut tree (theta %.2f, quadrupoles, leaves of %d, groups of "
      "%d), median of %d evaluations\n",
      sph::TreeGravity::default_opening_angle, sph::TreeGravity::default_leaf_size,
      sph::TreeGravity::default_group_size, repeats);
  std::printf("%-8s %7s %9s %9s %10s %10s %9s %7s %7s\n", "profile", "N", "build ms", "walk ms",
              "us/p", "us/p", "ns/inter", "pp", "pn");
  std::printf("%-8s %7s %9s %9s %10s %10s %9s %7s %7s\n", "", "", "", "",
              (std::to_string(threads) + " thr").c_str(), "1 thread", "", "", "");
  for (const std::size_t n : sizes) {
    const sph::Particles<3> profiles[2] = {sphere(n, false, 21), sphere(n, true, 22)};
    Measured measured[2];
    sph::TreeGravity tree;
    for (int r = 0; r < repeats; ++r) {
      for (int k = 0; k < 2; ++k) {  // the profiles alternate
        omp_set_num_threads(threads);
        measured[k].total.push_back(time_evaluation(tree, profiles[k]));
        measured[k].build.push_back(tree.statistics().build_seconds);
        measured[k].walk.push_back(tree.statistics().walk_seconds);
        measured[k].particle_interactions = tree.statistics().particle_interactions;
        measured[k].node_interactions = tree.statistics().node_interactions;
        omp_set_num_threads(1);
        measured[k].serial.push_back(time_evaluation(tree, profiles[k]));
      }
    }
    omp_set_num_threads(threads);
    for (int k = 0; k < 2; ++k) {
      const Measured& m = measured[k];
      const double per_particle = median(m.total) / static_cast<double>(n);
      const double interactions = m.particle_interactions + m.node_interactions;
      std::printf("%-8s %7zu %9.2f %9.2f %10.3f %10.3f %9.2f %7.0f %7.0f\n",
                  k == 0 ? "uniform" : "1/r", n, 1e3 * median(m.build), 1e3 * median(m.walk),
                  1e6 * per_particle, 1e6 * median(m.serial) / static_cast<double>(n),
                  1e9 * per_particle / interactions, m.particle_interactions, m.node_interactions);
    }
  }
  // Direct summation for comparison: every pair, exact.
  const std::size_t n = quick ? 2048 : 8192;
  const sph::Particles<3> p = sphere(n, false, 21);
  sph::DirectGravity direct;
  sph::TreeGravity tree;
  std::vector<double> direct_time, tree_time;
  for (int r = 0; r < (quick ? 2 : 3); ++r) {
    direct_time.push_back(time_evaluation(direct, p));
    tree_time.push_back(time_evaluation(tree, p));
  }
  std::printf("uniform  %7zu  direct summation %.3f us/p (%d thr), %.1f times the tree's %.3f\n", n,
              1e6 * median(direct_time) / static_cast<double>(n), threads,
              median(direct_time) / median(tree_time),
              1e6 * median(tree_time) / static_cast<double>(n));
}

}  // namespace bench
