#pragma once
/// \file
/// \brief app::run_evrard: one run of the Evrard collapse with its energy history, the
/// particles at t = 0.8, the extremes of its centre, its conservation errors and its cost; and
/// app::extremes, the peaks of an energy history.
///
/// The program names the scene (its terms and its gravity) and runs it:
///
/// \code
/// const app::EvrardRun run = app::run_evrard<Standard<sph::TreeGravity>>(
///     "standard", setup, {{}, sph::MonaghanGingold1983{}}, sph::TreeGravity{}, settings, 3.0);
/// const app::Extremes peaks = app::extremes(run);   // largest E_kin and E_th, deepest W
/// \endcode
///
/// The energies are recorded after every step.  With individual time steps they are recorded
/// only where all particles are synchronised (between, a particle in mid-step carries predicted
/// values and the potential of its last evaluation), which happens at the end of each block of
/// steps, and a block is as long as the longest step any particle allows: in the collapse that
/// left 61 records from t = 0 to 3, up to 0.19 apart, too few to draw the energies or read
/// their extremes.  So such a run ends a block at least every EvrardRun::record_interval
/// (0.01): about 300 records, for 9 % more particle updates in the standard viscosity's
/// collapse.  With one step for all the step is not cut.  The run stops at t = 0.8 to keep a copy
/// of the particles (the time of Selhammar's Figs 6-7) and the wall time and step count to
/// there, then goes on to the end.  A run that the simulation stops (a time step below its
/// minimum, a step budget exceeded, a non-finite value) is not an error here: the message is
/// kept in EvrardRun::stopped and the run returns what it recorded.
///
/// Header-only.  Chapter 6 runs the collapse with three viscosities, chapter 9 with the bulk
/// viscosity.

#include "app/particle_measures.hpp"
#include "app/progress.hpp"
#include "app/stopwatch.hpp"
#include "sph/error.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/reference/lagrangian_1d.hpp"
#include "sph/setups/evrard.hpp"
#include "sph/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace app {

/// What the chapter keeps of one run of the Evrard collapse.
struct EvrardRun {
  std::string name;
  int particles = 0;
  std::vector<double> t, kinetic, thermal, potential;  ///< after every step
  sph::Particles<3> at_08;                             ///< the particles at t = 0.8
  sph::Vec<3> centre_08 = sph::Vec<3>::Zero();         ///< their centre of mass
  sph::Particles<3> at_end;                            ///< the particles at the end
  double seconds_08 = 0, seconds = 0;                  ///< wall time to t = 0.8, to the end
  long steps_08 = 0, steps = 0;                        ///< steps to t = 0.8, to the end
  double peak_density = 0, t_peak = 0;  ///< the largest density of any particle, and when
  double least_h = INFINITY;            ///< the least smoothing length of any particle
  double least_dt = INFINITY;           ///< the least time step (not counting output times)
  std::string least_dt_criterion;       ///< what limited that step
  double momentum_drift = 0;            ///< at the end, see app::momentum_drift
  double energy_error_08 = 0, energy_error = 0;  ///< \f$ |E/E(0) - 1| \f$ at 0.8, at the end
  std::string stopped;                           ///< why the run stopped early, if it did
  /// The particle updates of the run (the particles each step evaluated: all of them, or with
  /// individual time steps those whose step ended), and how many of them a scheme of
  /// individual time steps would have made (with one step for all; see
  /// evrard_run_detail::individual_updates).
  double updates = 0, individual_updates = 0;
  /// With individual time steps, the longest time between two records of the energies.
  static constexpr double record_interval = 0.01;
};

/// The total energy of \p run at record \p k.
inline double total_at(const EvrardRun& run, std::size_t k) {
  return run.kinetic[k] + run.thermal[k] + run.potential[k];
}

namespace evrard_run_detail {

/// How many particles a scheme of individual time steps would update in one global step of the
/// simulation \p s: each particle takes the largest step \f$ \delta t_\mathrm{min}\,2^k \f$
/// its own limits allow (power-of-two bins above the least step, as GADGET and SWIFT arrange
/// them), and so counts \f$ 2^{-k} \f$ of an update per global step.  The ideal: it leaves out
/// what such a scheme costs besides (drifting every particle, a tree and a neighbour search
/// over all of them at every step of the smallest bin).
template <class Simulation>
double individual_updates(const Simulation& s) {
  thread_local std::vector<double> dt;
  s.particle_timesteps(dt);
  const double least = *std::min_element(dt.begin(), dt.end());
  if (!(least > 0 && std::isfinite(least))) return static_cast<double>(dt.size());
  double updates = 0;
  for (const double step : dt) {
    if (std::isfinite(step)) updates += std::exp2(-std::floor(std::log2(step / least)));
  }
  return updates;
}

/// Records the energies of the simulation \p s in \p run, and the extremes of its centre.
template <class Simulation>
void record(EvrardRun& run, const Simulation& s) {
  const auto& p = s.particles();
  if (s.synchronised()) {
    run.t.push_back(s.time());
    run.kinetic.push_back(sph::kinetic_energy(p));
    run.thermal.push_back(sph::thermal_energy(p));
    run.potential.push_back(s.potential_energy());
  }
  const auto densest = std::max_element(p.density.begin(), p.density.end());
  if (*densest > run.peak_density) {
    run.peak_density = *densest;
    run.t_peak = s.time();
  }
  run.least_h = std::min(run.least_h,
                         *std::min_element(p.smoothing_length.begin(), p.smoothing_length.end()));
  if (s.steps() > 0) {
    run.updates += static_cast<double>(s.evaluated());
    if constexpr (!Simulation::individual_steps) run.individual_updates += individual_updates(s);
  }
  if (s.steps() > 0 && s.last_limit().criterion != "output time" &&
      s.last_limit().dt < run.least_dt) {
    run.least_dt = s.last_limit().dt;
    run.least_dt_criterion = s.last_limit().criterion;
  }
}

}  // namespace evrard_run_detail

/// Runs the Evrard sphere \p setup with the scene \p Scene (its \p terms and \p gravity, an
/// ideal gas of the set-up's \f$ \gamma \f$, in open space) to \p t_end, recording after every
/// step; called \p name in its progress report, which \p show_progress false silences.
template <class Scene>
EvrardRun run_evrard(const std::string& name, const sph::EvrardSetup& setup,
                     const typename Scene::Terms& terms, const typename Scene::Gravity& gravity,
                     const sph::Settings& settings, double t_end, bool show_progress = true) {
  EvrardRun run;
  run.name = name;
  run.particles = setup.particles;
  const Stopwatch clock;
  sph::Simulation<Scene> sim(sph::make_evrard_sphere(setup), sph::Box<3>::open(), terms, gravity,
                             sph::IdealGas{setup.gamma}, settings);
  evrard_run_detail::record(run, sim);
  ProgressDisplay display = ProgressDisplay::automatic();
  display.report = nullptr;
  Progress progress(t_end, name, show_progress ? display : ProgressDisplay{});
  const auto on_step = [&](const auto& s) {
    evrard_run_detail::record(run, s);
    progress.update(s.steps() - 1, s.time(), s.last_limit().dt);
  };
  /// `run_until` advances the simulation to a time.  With individual time steps it goes there
  /// in pieces that end on multiples of `EvrardRun::record_interval`, so that a block ends, and
  /// the energies are recorded, at least that often.
  // (with individual time steps, a block ends at least every record_interval)
  const auto run_until = [&](double t) {
    if constexpr (sph::Simulation<Scene>::individual_steps) {
      const double interval = EvrardRun::record_interval;
      while (sim.time() < t) {
        double next = (std::floor(sim.time() / interval + 1e-6) + 1) * interval;
        if (next > t - 1e-6 * interval) next = t;
        sim.run_until(next, on_step);
      }
    } else {
      sim.run_until(t, on_step);
    }
  };
  /// The run: to t = 0.8, where it keeps the particles, their centre of mass, the cost so far
  /// and the energy error of the last record, which is at 0.8 itself (the last step is cut to
  /// end there); then on to the end.  A stop by the simulation (an sph::Error) is caught, as
  /// the file's comment says; any other exception still ends the program.
  try {
    run_until(std::min(0.8, t_end));
    run.at_08 = sim.particles();
    run.centre_08 = sph::centre_of_mass(sim.particles());
    run.seconds_08 = clock.seconds();
    run.steps_08 = sim.steps();
    run.energy_error_08 = std::abs(total_at(run, run.t.size() - 1) / total_at(run, 0) - 1);
    if (t_end > 0.8) run_until(t_end);
  } catch (const sph::Error& e) {
    run.stopped = e.what();
  }
  progress.finish();
  run.seconds = clock.seconds();
  run.steps = sim.steps();
  run.at_end = sim.particles();
  run.momentum_drift = app::momentum_drift(sim.particles(), sph::Vec<3>::Zero());
  run.energy_error = std::abs(total_at(run, run.t.size() - 1) / total_at(run, 0) - 1);
  return run;
}

/// The Evrard collapse computed in one dimension by lib/sph's Lagrangian code: its energies every
/// 0.005 in time, its profiles at t = 0.8 and at the end, and its shells' masses.
struct EvrardLagrangian {
  std::vector<double> t, kinetic, thermal, potential;
  sph::LagrangianProfile at_08, at_end;
  std::vector<double> zone_mass;
};

/// Runs sph::Lagrangian1D, \p zones equal-mass shells with self-gravity, from the Evrard
/// sphere's initial state (\f$ \rho = 1/(2\pi r) \f$, \f$ u = 0.05 \f$, at rest) to
/// \p t_end.  Spherical symmetry makes it the collapse's answer, to the accuracy of its shells:
/// chapter 6 checks it against an independent code's 4000 shells.
inline EvrardLagrangian run_evrard_lagrangian(int zones, double t_end) {
  sph::LagrangianOptions o;
  o.left = sph::LagrangianEnd::centre;
  o.self_gravity = true;
  const auto rho = [](double r) { return 1.0 / (2.0 * std::numbers::pi * r); };
  sph::Lagrangian1D sphere = sph::Lagrangian1D::from_profile(
      sph::LagrangianGeometry::spherical,
      sph::Lagrangian1D::equal_mass_edges(sph::LagrangianGeometry::spherical, 0.0, 1.0, zones, rho),
      rho, [](double) { return 0.0; }, [](double) { return 0.05; }, o);
  EvrardLagrangian run;
  double next = 0;
  const auto watch = [&](const sph::Lagrangian1D& s) {
    if (s.time() + 1e-12 < next) return;
    run.t.push_back(s.time());
    run.kinetic.push_back(s.kinetic_energy());
    run.thermal.push_back(s.thermal_energy());
    run.potential.push_back(s.potential_energy());
    next += 0.005;
  };
  watch(sphere);
  sphere.run_until(std::min(0.8, t_end), watch);
  run.at_08 = sphere.profile();
  if (t_end > 0.8) sphere.run_until(t_end, watch);
  run.at_end = sphere.profile();
  run.zone_mass = sphere.zone_mass();
  return run;
}

/// The extremes of an energy history: the largest kinetic and thermal energy and the deepest
/// potential energy, each with the time it was reached.
struct Extremes {
  double kinetic = 0, t_kinetic = 0, thermal = 0, t_thermal = 0, potential = 0, t_potential = 0;
};

/// The extremes of the history \p t -> (\p kinetic, \p thermal, \p potential).
inline Extremes extremes(const std::vector<double>& t, const std::vector<double>& kinetic,
                         const std::vector<double>& thermal, const std::vector<double>& potential) {
  Extremes x;
  for (std::size_t k = 0; k < t.size(); ++k) {
    if (kinetic[k] > x.kinetic) x.kinetic = kinetic[k], x.t_kinetic = t[k];
    if (thermal[k] > x.thermal) x.thermal = thermal[k], x.t_thermal = t[k];
    if (potential[k] < x.potential) x.potential = potential[k], x.t_potential = t[k];
  }
  return x;
}

/// The extremes of the energy history of \p run.
inline Extremes extremes(const EvrardRun& run) {
  return extremes(run.t, run.kinetic, run.thermal, run.potential);
}

}  // namespace app
