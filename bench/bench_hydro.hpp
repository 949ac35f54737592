#pragma once
// The cost of one hydrodynamic step: Sod's tube in 1D, 2D and 3D at fixed N with the
// Monaghan-Gingold viscosity (alpha = 1, beta = 2), timed over a fixed number of steps after a
// warm-up, with 1 thread and with all threads.  Reported as microseconds per particle-step and
// nanoseconds per neighbour pair (an (i, j) entry of the neighbour list, each pair counted
// from both sides, as the gather passes visit it).

#include "sph/setups/shock_tube.hpp"
#include "sph/simulation.hpp"
#include "sph/terms/monaghan_gingold_1983.hpp"
#include "sph/terms/morris_monaghan_1997.hpp"
#include "sph/terms/pressure.hpp"
#include "sph/terms/selhammar_1997.hpp"
#include "sph/terms/watkins_1996.hpp"

#include <omp.h>

#include <chrono>
#include <memory>
#include <cstdio>
#include <string>

namespace bench {

struct StepCost {
  std::size_t particles = 0;
  double neighbours = 0;  // mean list entries per particle
  double us_per_particle_step = 0;
  double ns_per_pair = 0;
  bool identical_to_one_thread = true;
};

// The scene: the pressure force and the Monaghan-Gingold viscosity, nothing else.
template <int D>
struct Sod : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
};
template <int D>
using SodSimulation = sph::Simulation<Sod<D>>;

// A term that only asks the density loop for the velocity-derivative fields (rho-dot, div v,
// curl v): what Selhammar's restricted viscosity and a viscosity switch will ask for.  The
// bench shows what naming them costs.
struct AsksForVelocityFields {
  static constexpr const char* name = "asks for rho-dot, div v, curl v";
  static constexpr sph::Needs needs =
      sph::Needs::density_rate | sph::Needs::velocity_divergence | sph::Needs::velocity_curl;
};
template <int D>
struct SodWithFields : sph::Scene<D> {
  using Terms =
      sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983, AsksForVelocityFields>;
};

// The other viscosities of chapter 5: Selhammar's modified viscosity (restricted vNR term and
// collective term, with their density rate and gradient pass) and the Morris-Monaghan switch.
template <int D>
struct SodModified : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::RestrictedVonNeumannRichtmyer,
                           sph::SelhammarCollective<D>>;
};
template <int D>
struct SodSwitch : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MorrisMonaghan1997>;
};
// Chapter 9's bulk viscosity in place of the artificial one (Watkins' two passes, mu_b =
// rho c h / 8): a gradient pass more, and a non-central pair acceleration in the force pass.
template <int D>
struct SodBulk : sph::Scene<D> {
  using Terms = sph::Terms<sph::PressureHernquistKatz,
                           sph::WatkinsViscosity<D, sph::Kernel<D>, sph::ArtificialBulk>>;
};

// Sod's tube in D dimensions, left spacing as given, with the scene's terms at their default
// parameters (the Monaghan-Gingold viscosity: alpha = 1, beta = 2).
template <int D, class Scene = Sod<D>>
std::unique_ptr<sph::Simulation<Scene>> make_sod(double left_spacing,
                                                 const sph::SmoothingLengthRule& rule,
                                                 double fixed_timestep = 0) {
  sph::ShockTubeSetup setup = sph::ShockTubeSetup::sod();
  setup.left_spacing = left_spacing;
  sph::Settings settings;
  settings.smoothing = rule;
  settings.fixed_timestep = fixed_timestep;
  const auto tube = sph::make_shock_tube<D>(setup, rule);
  return std::make_unique<sph::Simulation<Scene>>(
      tube.particles, tube.box, sph::IdealGas(setup.gamma), typename Scene::Terms{}, settings);
}

// Run `steps` steps of a Sod tube in D dimensions with the given threads.
template <int D, class Scene = Sod<D>>
StepCost time_sod_steps(double left_spacing, const sph::SmoothingLengthRule& rule, int threads,
                        int steps, sph::Particles<D>* final_state = nullptr,
                        double fixed_timestep = 0) {
  omp_set_num_threads(threads);
  const auto simulation = make_sod<D, Scene>(left_spacing, rule, fixed_timestep);
  auto& sim = *simulation;
  for (int k = 0; k < 3; ++k) sim.step();  // warm-up: caches, allocations
  const auto start = std::chrono::steady_clock::now();
  double entries = 0;
  for (int k = 0; k < steps; ++k) {
    sim.step();
    entries += static_cast<double>(sim.neighbours().entries());
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  StepCost cost;
  cost.particles = sim.particles().size();
  cost.neighbours = entries / steps / static_cast<double>(cost.particles);
  cost.us_per_particle_step = 1e6 * seconds / steps / static_cast<double>(cost.particles);
  cost.ns_per_pair = 1e9 * seconds / entries;
  if (final_state) *final_state = sim.particles();
  return cost;
}

template <int D>
bool same_state(const sph::Particles<D>& a, const sph::Particles<D>& b) {
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (a.position[i] != b.position[i] || a.velocity[i] != b.velocity[i] ||
        a.internal_energy[i] != b.internal_energy[i])
      return false;
  }
  return a.size() == b.size();
}

// One line of the table: 1 thread, then all threads, and whether the two agree bitwise.
template <int D>
void report_sod(const char* label, double left_spacing, const sph::SmoothingLengthRule& rule,
                int steps, const char* reference) {
  const int threads = omp_get_num_procs();
  sph::Particles<D> one, all;
  const StepCost serial = time_sod_steps<D>(left_spacing, rule, 1, steps, &one);
  const StepCost parallel = time_sod_steps<D>(left_spacing, rule, threads, steps, &all);
  std::printf("%-4s %8zu %7.1f %10.3f %10.3f %9.1f %9.1f   %-9s %s\n", label, serial.particles,
              serial.neighbours, serial.us_per_particle_step, parallel.us_per_particle_step,
              serial.ns_per_pair, parallel.ns_per_pair, same_state(one, all) ? "yes" : "NO",
              reference);
}

// A whole run to t = 0.2 with all threads: the mean cost per particle-step over the run.  The
// 40 timed steps above come early, while most of the gas still rests and keeps its neighbour
// candidates (see NeighbourSearch::try_reuse); later more of it moves and is searched again.
template <int D>
void report_whole_run(const char* label, double left_spacing,
                      const sph::SmoothingLengthRule& rule) {
  const int threads = omp_get_num_procs();
  omp_set_num_threads(threads);
  const auto simulation = make_sod<D>(left_spacing, rule);
  auto& sim = *simulation;
  const auto start = std::chrono::steady_clock::now();
  const double t_end = 0.2;  // Sod's time
  sim.run_until(t_end);
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto& search = sim.neighbour_search();
  std::printf(
      "%-4s %8zu  whole run to t = %.2f: %ld steps, %.1f s, %.3f us/p-step (%d thr); neighbour "
      "search: %ld of %ld "
      "updates searched, %.1f %% of the particles per step\n",
      label, sim.particles().size(), t_end, sim.steps(), seconds,
      1e6 * seconds / static_cast<double>(sim.steps()) /
          static_cast<double>(sim.particles().size()),
      threads, search.searches(), search.searches() + search.reuses(),
      100.0 * static_cast<double>(search.particle_searches()) /
          static_cast<double>(search.searches() + search.reuses()) /
          static_cast<double>(sim.particles().size()));
}

inline void bench_viscosities(bool quick);

inline void bench_hydro(bool quick) {
  const int steps = quick ? 5 : 40;
  const int threads = omp_get_num_procs();
  std::printf(
      "\nHydrodynamic step, Sod tube with Monaghan-Gingold AV (alpha 1, beta 2), %d steps timed\n",
      steps);
  std::printf("%-4s %8s %7s %10s %10s %9s %9s   %-9s %s\n", "dim", "N", "ngb", "us/p-step",
              "us/p-step", "ns/pair", "ns/pair", "bitwise", "reference (mature code, 1 thread)");
  std::printf("%-4s %8s %7s %10s %10s %9s %9s   %-9s\n", "", "", "", "1 thread",
              (std::to_string(threads) + " thr").c_str(), "1 thread",
              (std::to_string(threads) + " thr").c_str(), "1 = N thr");
  report_sod<1>("1D", quick ? 1.0 / 800 : 1.0 / 25600, sph::SmoothingLengthRule::from_density(4.0),
                steps, "0.38 us/p-step; target <= 0.15 (2 threads)");
  report_sod<2>("2D", quick ? 1.0 / 80 : 1.0 / 320,
                sph::SmoothingLengthRule::neighbour_number(20, 2), steps, "");
  report_sod<3>("3D", quick ? 1.0 / 40 : 1.0 / 160,
                sph::SmoothingLengthRule::neighbour_number(60, 3), steps,
                "14 us/p-step at ~55 ngb; target <= 0.5 (2 threads)");
  if (!quick)
    report_whole_run<3>("3D", 1.0 / 160, sph::SmoothingLengthRule::neighbour_number(60, 3));
  // What a term costs when it is named: the same 3D tube with rho-dot, div v and curl v summed
  // in the density loop (a scene that does not name them runs the plain loop above).
  const double spacing = quick ? 1.0 / 40 : 1.0 / 160;
  const auto rule = sph::SmoothingLengthRule::neighbour_number(60, 3);
  const StepCost plain = time_sod_steps<3>(spacing, rule, threads, steps);
  const StepCost fields = time_sod_steps<3, SodWithFields<3>>(spacing, rule, threads, steps);
  std::printf(
      "3D %8zu  with rho-dot, div v, curl v named: %.3f us/p-step against %.3f without (%d thr, "
      "%+.0f %%)\n",
      fields.particles, fields.us_per_particle_step, plain.us_per_particle_step, threads,
      100.0 * (fields.us_per_particle_step / plain.us_per_particle_step - 1.0));
  bench_viscosities(quick);
}

// Chapter 5's viscosities and chapter 9's bulk viscosity against the standard one (target: the
// modified step <= 1.3 times), all with the same fixed step, so that each step moves the
// particles as far and the neighbour search reuses its candidates as often (with its own step,
// a viscosity with a longer step would pay more searching per step, and less per unit of
// time).  `--only viscosities` runs this part alone (for a profile, or an A/B of two builds).
inline void bench_viscosities(bool quick) {
  const int steps = quick ? 5 : 40;
  const int threads = omp_get_num_procs();
  const double spacing = quick ? 1.0 / 40 : 1.0 / 160;
  const auto rule = sph::SmoothingLengthRule::neighbour_number(60, 3);
  const double dt = 2e-4;
  const StepCost standard = time_sod_steps<3>(spacing, rule, threads, steps, nullptr, dt);
  const StepCost modified =
      time_sod_steps<3, SodModified<3>>(spacing, rule, threads, steps, nullptr, dt);
  const StepCost with_switch =
      time_sod_steps<3, SodSwitch<3>>(spacing, rule, threads, steps, nullptr, dt);
  const StepCost bulk = time_sod_steps<3, SodBulk<3>>(spacing, rule, threads, steps, nullptr, dt);
  // (the standard step again, last: a drift of the machine shows as a difference of the two)
  const StepCost again = time_sod_steps<3>(spacing, rule, threads, steps, nullptr, dt);
  std::printf(
      "3D %8zu  fixed step %g: standard %.3f us/p-step (%.3f timed again last);\n"
      "    Selhammar's modified viscosity %.3f (%.2f x); Morris-Monaghan switch %.3f (%.2f x); "
      "Watkins' bulk viscosity %.3f (%.2f x)\n",
      modified.particles, dt, standard.us_per_particle_step, again.us_per_particle_step,
      modified.us_per_particle_step, modified.us_per_particle_step / standard.us_per_particle_step,
      with_switch.us_per_particle_step,
      with_switch.us_per_particle_step / standard.us_per_particle_step, bulk.us_per_particle_step,
      bulk.us_per_particle_step / standard.us_per_particle_step);
}

}  // namespace bench
