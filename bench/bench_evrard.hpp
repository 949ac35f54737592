#pragma once
// The cost of the whole Evrard step (chapter 6): hydrodynamics with the standard or the
// modified viscosity, plus tree gravity, on the machine's threads.  Measured at two moments of
// the collapse -- the first steps (the sphere as set up) and around t = 0.8, when the centre has
// collapsed and the neighbour search and the tree work hardest -- as microseconds per
// particle-step, with the gravity evaluation alone timed on the same particles, so that the
// hydrodynamic part is the difference; and the share of particles whose neighbours were
// searched again (the others kept their candidates); the standard one again with the tree's
// relative criterion, with 56 neighbours instead of the paper's 64 (the set-up of the
// production code the step's target was set against), and with both.  Then, unless --quick,
// the whole 8192-particle collapse to t = 3 (the chapter's Fig 5 run): with one step for all,
// with individual time steps, and with both individual steps and the relative criterion.

#include "sph/gravity/tree.hpp"
#include "sph/integration/individual_leapfrog.hpp"
#include "sph/setups/evrard.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/terms/selhammar_1997.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

namespace bench {

struct EvrardStandard : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::MonaghanGingold1983>;
  using Gravity = sph::TreeGravity;
};
struct EvrardStandardOwnSteps : EvrardStandard {
  using Integrator = sph::IndividualLeapfrog<3>;
};
struct EvrardModified : sph::Scene<3> {
  using Terms = sph::Terms<sph::PressureOwnWork, sph::RestrictedVonNeumannRichtmyer,
                           sph::SelhammarCollective<3>>;
  using Gravity = sph::TreeGravity;
};

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Median over `repeats` blocks of `steps` steps: microseconds per particle-step of the whole
// step, and of its gravity (the tree's own build and walk time).
template <class Scene>
void time_block(sph::Simulation<Scene>& sim, int steps, int repeats, const char* label) {
  const double n = static_cast<double>(sim.particles().size());
  const long searched_before = sim.neighbour_search().particle_searches();
  std::vector<double> whole, gravity;
  for (int r = 0; r < repeats; ++r) {
    double g = 0;
    const auto t0 = std::chrono::steady_clock::now();
    for (int s = 0; s < steps; ++s) {
      sim.step();
      g += sim.gravity().statistics().build_seconds + sim.gravity().statistics().walk_seconds;
    }
    whole.push_back(seconds_since(t0) * 1e6 / (steps * n));
    gravity.push_back(g * 1e6 / (steps * n));
  }
  std::sort(whole.begin(), whole.end());
  std::sort(gravity.begin(), gravity.end());
  const double w = whole[whole.size() / 2], g = gravity[gravity.size() / 2];
  double rho_max = 0;
  for (double rho : sim.particles().density) rho_max = std::max(rho_max, rho);
  const double searched =
      static_cast<double>(sim.neighbour_search().particle_searches() - searched_before) /
      (n * steps * repeats);
  std::printf(
      "  %-40s t = %5.3f  rho_max %6.0f  step %5.2f us/particle, gravity %5.2f, "
      "the rest %5.2f; searched %4.1f %%\n",
      label, sim.time(), rho_max, w, g, w - g, 100 * searched);
}

template <class Scene>
void bench_evrard_scene(int particles, const typename Scene::Terms& terms, const char* name,
                        bool quick, const sph::TreeGravity& tree = {},
                        const sph::Settings& settings = {}) {
  sph::EvrardSetup setup;
  setup.particles = particles;
  sph::Simulation<Scene> sim(sph::make_evrard_sphere(setup), sph::Box<3>::open(), terms,
                             sph::IdealGas{setup.gamma}, tree, settings);
  char label[96];
  std::snprintf(label, sizeof label, "%s, N = %d, start", name, particles);
  time_block(sim, quick ? 2 : 5, quick ? 1 : 3, label);
  if (quick) return;
  sim.run_until(0.78);
  std::snprintf(label, sizeof label, "%s, N = %d, t = 0.8", name, particles);
  time_block(sim, 5, 3, label);
}

inline void bench_evrard(bool quick) {
  std::printf("\nEvrard collapse: the whole step (hydro + tree gravity), %d threads\n",
              omp_get_max_threads());
  const sph::MonaghanGingold1983 standard{1, 2, 1e-4};
  for (int n : {8192, 22000}) {
    if (quick && n > 8192) break;
    bench_evrard_scene<EvrardStandard>(n, {{}, standard}, "standard", quick);
    bench_evrard_scene<EvrardModified>(n, {{}, {2, 1e-4}, {1, 64}}, "modified", quick);
  }
  // The tree's relative opening criterion (GADGET-2's) at its default alpha: on the collapsed
  // centre it takes 44 % fewer multipoles than theta = 0.3 for a smaller largest error.
  sph::TreeGravity relative;
  relative.criterion = sph::TreeGravity::Criterion::relative;
  bench_evrard_scene<EvrardStandard>(quick ? 8192 : 22000, {{}, standard}, "standard, relative",
                                     quick, relative);
  // The production code the target was set against ran its collapse with 56 neighbours; the
  // paper's 64 make an eighth more pairs.  The same step with 56, like for like.
  sph::Settings fewer;
  fewer.smoothing = sph::SmoothingLengthRule::neighbour_number(56);
  bench_evrard_scene<EvrardStandard>(quick ? 8192 : 22000, {{}, standard},
                                     "standard, 56 neighbours", quick, {}, fewer);
  // Both: the production code's neighbour number, and an opening criterion whose forces meet
  // the same accuracy targets as theta = 0.3 (chapter 6, Step 2) with fewer interactions.
  bench_evrard_scene<EvrardStandard>(quick ? 8192 : 22000, {{}, standard},
                                     "standard, 56 neighbours, relative", quick, relative, fewer);
  if (quick) return;
  sph::EvrardSetup setup;
  const auto t0 = std::chrono::steady_clock::now();
  sph::Simulation<EvrardStandard> sim(sph::make_evrard_sphere(setup), sph::Box<3>::open(),
                                      EvrardStandard::Terms{{}, standard},
                                      sph::IdealGas{setup.gamma});
  sim.run_until(3.0);
  const double s = seconds_since(t0);
  std::printf(
      "  the 8192-particle collapse to t = 3, standard viscosity: %ld steps, %.1f s, "
      "%.2f us per particle-step\n",
      sim.steps(), s, s * 1e6 / (double(sim.steps()) * 8192));
  // The same with individual time steps: how many particles each step updated, and the cost of
  // one particle's update (each step also searches, drifts and builds the tree for all).
  const auto t1 = std::chrono::steady_clock::now();
  sph::Simulation<EvrardStandardOwnSteps> own(sph::make_evrard_sphere(setup), sph::Box<3>::open(),
                                              EvrardStandard::Terms{{}, standard},
                                              sph::IdealGas{setup.gamma});
  double updates = 0;
  own.run_until(3.0, [&](const auto& o) { updates += static_cast<double>(o.evaluated()); });
  const double s_own = seconds_since(t1);
  std::printf(
      "  the same with individual time steps: %ld steps, %.1f s (%.2f of one step for all);\n"
      "    %.0f particles updated a step on average, %.2f of one step for all's updates; "
      "%.2f us per particle update\n",
      own.steps(), s_own, s_own / s, updates / double(own.steps()),
      updates / (double(sim.steps()) * 8192), s_own * 1e6 / updates);
  // And with the tree's relative criterion as well.
  const auto t2 = std::chrono::steady_clock::now();
  sph::Simulation<EvrardStandardOwnSteps> both(sph::make_evrard_sphere(setup), sph::Box<3>::open(),
                                               EvrardStandard::Terms{{}, standard},
                                               sph::IdealGas{setup.gamma}, relative);
  both.run_until(3.0);
  std::printf("  the same with the tree's relative criterion too: %ld steps, %.1f s (%.2f)\n",
              both.steps(), seconds_since(t2), seconds_since(t2) / s);
}

}  // namespace bench
