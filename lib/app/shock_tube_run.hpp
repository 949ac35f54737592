#pragma once
/// \file
/// \brief app::run_shock_tube: build a shock tube, integrate it to a given time, and keep what
/// the chapters measure of it -- the particles, the exact solution, the cost and the two
/// conservation checks.
///
/// Chapters 3 and 4 run dozens of shock tubes, with different schemes, dimensions, starts and
/// smoothing-length rules.  Each run is the same few steps: build the tube
/// (sph::make_shock_tube), hand it to a simulation of the chosen scene with its gas (tube_gas:
/// an ideal gas of the tube's \f$ \gamma \f$, or each side's adiabat), integrate with a
/// progress line, and measure the totals before and after.  They live here once:
///
/// \code
/// template <int D>
/// struct ViscousGas : sph::Scene<D> {
///   using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
/// };
/// const auto run = app::run_shock_tube<ViscousGas<1>>(
///     sph::ShockTubeSetup::sod(), sph::SmoothingLengthRule::from_density(4),
///     {{}, sph::MonaghanGingold1983(1, 2)}, {.t_end = 0.2, .label = "Sod 1D"});
/// const auto errors = sph::shock_tube_errors(run.particles, run.exact, 0.2);
/// \endcode
///
/// The wall time is that of the integration alone.  Building the tube -- in 2D and 3D that
/// includes settling each side to a glass -- is not part of what a scheme costs.  (The whole
/// run, building included, is TubeRun::total_seconds.)
///
/// **Only where the exact solution applies.**  The runner refuses an end time past the one
/// until which the exact solution describes the measured window (sph::exact_solution_validity):
/// with walls, when the fastest wave reaches a wall; in a periodic tube, when the waves of the
/// far interface at \f$ x = \pm L \f$ reach the window or meet the waves from the centre.  The
/// message names that time and the time the fastest wave reaches the tube's end.  A tube whose
/// two gases move (a boosted tube) is compared in the frame that moves with the mean of their
/// velocities: the particles are returned shifted back by \f$ v_f t \f$ (wrapped into the tube)
/// with \f$ v_f \f$ taken off their velocities, and the exact solution is that of the tube at
/// rest in that frame.  The two are then compared exactly as for a tube at rest.
///
/// declare_tube_states makes the tube's two states options of a chapter, so that a reader can
/// run any Riemann problem through the same program.
///
/// Header-only, like the other shared pieces of lib/app that use lib/sph.

#include "app/chapter.hpp"
#include "app/progress.hpp"
#include "app/stopwatch.hpp"
#include "sph/boundaries/fixed_particles.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/setups/shock_tube.hpp"
#include "sph/simulation.hpp"

#include <cmath>
#include <ctime>
#include <string>
#include <type_traits>

namespace app {

/// What a shock-tube run prints while it runs.
enum class RunReport {
  none,           ///< nothing
  live,           ///< a progress line on a terminal (standard error), cleared at the end
  live_and_final  ///< the same, and a one-line report on standard output at the end
};

/// How a shock tube is integrated and reported.
struct TubeRunOptions {
  double t_end = 0.2;    ///< the run stops at this time
  double courant = 0.3;  ///< \f$ \varepsilon \f$ of the time step
  /// Selhammar's eq 7 or the signal velocity of Monaghan (1997) (sph::Settings)
  sph::Settings::TimestepRule timestep_rule = sph::Settings::TimestepRule::selhammar_eq7;
  std::string label = "shock tube";  ///< names the run in the progress line and TubeRun::name
  RunReport report = RunReport::live;
};

/// What a chapter keeps of one run.
template <int D>
struct TubeRun {
  std::string name;             ///< the label it ran under
  sph::Particles<D> particles;  ///< at the end time
  sph::RiemannSolution exact;   ///< the Riemann problem of the tube's two states
  int in_window = 0;            ///< particles in the window \f$ |x| \le 0.5 \f$ at t = 0
  long steps = 0;               ///< time steps taken
  double seconds = 0;           ///< wall time of the integration
  double total_seconds = 0;     ///< wall time of the whole run: building the tube and integrating
  /// CPU time of the process over the whole run (all its threads): on one thread of a quiet
  /// machine the same as total_seconds, on a loaded one without the time others took
  double cpu_seconds = 0;
  double frame_velocity = 0;  ///< the frame the run is compared in (see the file comment)
  double energy_change = 0;   ///< \f$ |E(t) - E(0)|/E(0) \f$, E kinetic plus thermal
  /// \f$ |\mathbf P(t) - \mathbf P(0) + \mathbf J_{\rm walls}| / \sum_i m_i|\mathbf v_i(t)| \f$,
  /// with \f$ \mathbf J_{\rm walls} \f$ the impulse the walls took up (wall_impulse), see
  /// sph::momentum_scale
  double momentum_drift = 0;
  /// The x momentum the walls of a walled tube took up from the gas (0 for a periodic tube):
  /// the gas's momentum changes by minus this, and momentum_drift counts the two together
  double wall_impulse = 0;
  std::size_t left_count = 0;  ///< the first left_count particles began on the left
  std::string limit;           ///< what limited the last full time step, e.g. "Courant (eq 7)"
};

/// The gas of the tube \p tube made from \p setup: an ideal gas of the tube's \f$ \gamma \f$,
/// or with sph::Adiabats each particle on the adiabat of the state it starts in,
/// \f$ K = P/\rho^\gamma \f$ of its side (the polytrope Watkins et al. print, chapter 9).
template <class Eos, int D>
Eos tube_gas(const sph::ShockTubeSetup& setup, const sph::ShockTube<D>& tube) {
  if constexpr (std::is_same_v<Eos, sph::Adiabats>) {
    std::vector<double> K(tube.particles.size());
    for (std::size_t i = 0; i < K.size(); ++i) {
      const sph::GasState& side =
          i < static_cast<std::size_t>(tube.left_count) ? setup.left : setup.right;
      K[i] = side.pressure / std::pow(side.density, setup.gamma);
    }
    return sph::Adiabats(std::move(K), setup.gamma);
  } else {
    return Eos(setup.gamma);
  }
}

/// Builds the tube of \p setup with the smoothing-length rule \p rule, integrates it to
/// `options.t_end` with the scene \p Scene (its terms given by \p terms, its gas made by
/// tube_gas, the Courant factor of the options) and returns the final state and
/// what was measured on the way.  Errors of the simulation (a time step that collapses, a
/// non-finite force) propagate as sph::Error.
template <class Scene>
TubeRun<Scene::D> run_shock_tube(const sph::ShockTubeSetup& setup,
                                 const sph::SmoothingLengthRule& rule,
                                 const typename Scene::Terms& terms,
                                 const TubeRunOptions& options = {}) {
  constexpr int D = Scene::D;
  const Stopwatch whole_run;
  const std::clock_t cpu_start = std::clock();
  const sph::ExactValidity validity = sph::exact_solution_validity(setup);
  if (!(options.t_end <= validity.until)) {
    throw sph::Error("shock tube: no exact solution to compare with at t = " +
                     sph::show(options.t_end) + " (lower the end time): " + validity.reason);
  }
  const sph::ShockTube<D> tube = sph::make_shock_tube<D, typename Scene::Kernel>(setup, rule);
  TubeRun<D> run;
  run.name = options.label;
  run.exact = tube.exact;
  run.frame_velocity = validity.frame_velocity;
  run.left_count = static_cast<std::size_t>(tube.left_count);
  const sph::Selection window = sph::shock_tube_window();
  for (std::size_t i = 0; i < tube.particles.size(); ++i) {
    run.in_window += window.contains<D>(i, tube.particles.position[i]);
  }

  sph::Settings settings;
  settings.smoothing = rule;
  settings.courant = options.courant;
  settings.timestep_rule = options.timestep_rule;
  const Stopwatch clock;
  sph::Simulation<Scene> sim(tube.particles, tube.box, tube_gas<typename Scene::Eos>(setup, tube),
                             terms, settings);
  const auto energy = [](const sph::Particles<D>& p) {
    return sph::kinetic_energy(p) + sph::thermal_energy(p);
  };
  const double energy_before = energy(sim.particles());
  const sph::Vec<D> momentum_before = sph::total_momentum(sim.particles());
  // A tube closed by walls: the walls' fixed particles push on the gas through the same pair
  // terms as the gas pushes on them, so the gas's momentum changes by what the walls take up.
  // They are never kicked, but the force on them is computed; the leapfrog's impulse on them
  // over a step is the mean of the forces at its two ends times the step.
  // (A scene without fixed particles skips the sum.)
  const auto force_on_walls = [](const sph::Particles<D>& p) {
    sph::Vec<D> force = sph::Vec<D>::Zero();
    if constexpr (std::is_same_v<typename Scene::Boundaries, sph::FixedParticles>) {
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (p.kind[i] == sph::ParticleKind::fixed) force += p.mass[i] * p.acceleration[i];
      }
    }
    return force;
  };
  sph::Vec<D> wall_force = force_on_walls(sim.particles());
  sph::Vec<D> wall_impulse = sph::Vec<D>::Zero();
  double t_last = sim.time();

  ProgressDisplay display = ProgressDisplay::automatic();
  if (options.report != RunReport::live_and_final) display.report = nullptr;
  if (options.report == RunReport::none) display.live = nullptr;
  Progress progress(options.t_end, options.label, display);
  sim.run_until(options.t_end, [&](const sph::Simulation<Scene>& s) {
    progress.update(s.steps() - 1, s.time(),
                    s.last_limit().dt);  // (update takes the index of the step)
    if (s.last_limit().criterion != "output time") run.limit = s.last_limit().criterion;
    const sph::Vec<D> force = force_on_walls(s.particles());
    wall_impulse += 0.5 * (wall_force + force) * (s.time() - t_last);
    wall_force = force;
    t_last = s.time();
  });
  progress.finish();

  run.particles = sim.particles();
  run.steps = sim.steps();
  run.seconds = clock.seconds();
  run.energy_change = std::abs(energy(run.particles) - energy_before) / energy_before;
  // (the walls' particles are at rest: the total momentum is the gas's)
  const sph::Vec<D> momentum_change = sph::total_momentum(run.particles) - momentum_before;
  run.wall_impulse = wall_impulse[0];
  run.momentum_drift = (momentum_change + wall_impulse).norm() / sph::momentum_scale(run.particles);
  if (run.frame_velocity != 0) {
    // Into the frame moving with v_f: positions back by v_f t, velocities less v_f.
    const double shift = run.frame_velocity * options.t_end;
    for (std::size_t i = 0; i < run.particles.size(); ++i) {
      run.particles.position[i][0] -= shift;
      run.particles.position[i] = tube.box.wrap(run.particles.position[i]);
      run.particles.velocity[i][0] -= run.frame_velocity;
    }
    sph::GasState left = setup.left, right = setup.right;
    left.velocity -= run.frame_velocity;
    right.velocity -= run.frame_velocity;
    run.exact = sph::RiemannSolution(left, right, setup.gamma);
  }
  run.total_seconds = whole_run.seconds();
  run.cpu_seconds = static_cast<double>(std::clock() - cpu_start) / CLOCKS_PER_SEC;
  return run;
}

/// Declares the two states of a tube and its \f$ \gamma \f$ as options of \p chapter, bound to
/// \p setup: `--rho-left`, `--p-left`, `--v-left`, `--v-right`, `--rho-right`, `--p-right` and
/// `--gamma`, with the defaults \p setup has.  Densities and pressures lie in
/// \f$ [10^{-3}, 10^3] \f$, speeds in \f$ [-10, 10] \f$ (a faster gas needs proportionally
/// more steps, and crosses the periodic tube before the run ends) and \f$ \gamma \f$ in
/// \f$ (1, 3] \f$; two states that fly apart into a vacuum are refused later, by the exact
/// solver, with a message that says so.
inline void declare_tube_states(Chapter& chapter, sph::ShockTubeSetup& setup) {
  chapter.parameter("--rho-left", setup.left.density, "shock tube: density on the left")
      .check(between(1e-3, 1e3));
  chapter.parameter("--p-left", setup.left.pressure, "shock tube: pressure on the left")
      .check(between(1e-3, 1e3));
  chapter.parameter("--v-left", setup.left.velocity, "shock tube: velocity on the left")
      .check(between(-10, 10));
  chapter.parameter("--v-right", setup.right.velocity, "shock tube: velocity on the right")
      .check(between(-10, 10));
  chapter.parameter("--rho-right", setup.right.density, "shock tube: density on the right")
      .check(between(1e-3, 1e3));
  chapter.parameter("--p-right", setup.right.pressure, "shock tube: pressure on the right")
      .check(between(1e-3, 1e3));
  chapter.parameter("--gamma", setup.gamma, "adiabatic index")
      .check(greater_than(1.0))
      ->check(at_most(3.0));
}

}  // namespace app
