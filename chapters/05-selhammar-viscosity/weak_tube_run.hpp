#pragma once
/// \file
/// \brief Selhammar's weak shock tube: app::run_weak_tube integrates it to t = 20 and keeps the
/// particles, the cost and the two conservation measures; app::weak_tube_reference computes the
/// one-dimensional Lagrangian solution it is measured against, and the helpers below read
/// errors and totals off the two.
///
/// The tube (sph::make_weak_tube) is a dense slab beside a thin gas in a
/// \f$ 1 \times 1 \times 9 \f$ box, periodic across and open at both ends.  The chapter runs
/// it with several viscosities and readings, so the run is written once; step2_readings(),
/// below, shows the calls: a run, its reference, and the errors read off the two.
///
/// The run pauses at evenly spaced times (twice by default: t = 10 and 20) and hands the
/// simulation to a callable, so that the chapter can take a census of its terms there without
/// this file knowing which terms a scene has.
///
/// Header-only, like the chapter's other files that use lib/sph.

#include "app/curve_reading.hpp"
#include "app/particle_measures.hpp"
#include "app/progress.hpp"
#include "app/stopwatch.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/reference/lagrangian_1d.hpp"
#include "sph/reference/riemann.hpp"
#include "sph/setups/selhammar_problems.hpp"
#include "sph/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

namespace app {

/// What the chapter keeps of one run of the weak tube.
struct WeakTubeRun {
  std::string name;
  sph::Particles<3> particles;  ///< at the end time
  long steps = 0;
  double seconds = 0;         ///< wall time, the simulation's set-up included
  double momentum_drift = 0;  ///< \f$ |\mathbf P(t) - \mathbf P(0)| / \sum m|\mathbf v| \f$
  double energy_change = 0;   ///< \f$ |E(t) - E(0)|/E(0) \f$, E kinetic plus thermal
};

/// How long the weak tube runs, and how often it pauses for the caller.
struct WeakTubeRunOptions {
  double t_end = 20.0;  ///< Selhammar shows the tube at t = 20
  int pauses = 2;       ///< the caller's callable runs at t_end k / pauses, k = 1 .. pauses
};

/// A callable that does nothing at a pause.
struct NoPause {
  template <class Sim>
  void operator()(const Sim&, int) const {}
};

/// Runs the weak tube of \p setup with the scene \p Scene (its terms \p terms, an ideal gas of
/// the set-up's \f$ \gamma \f$, the step of \p settings) to `options.t_end`, with a progress
/// line named \p name.  At each pause k (0, 1, ...) it calls `at_pause(simulation, k)`.
template <class Scene, class AtPause = NoPause>
WeakTubeRun run_weak_tube(const std::string& name, const sph::WeakTubeSetup& setup,
                          const typename Scene::Terms& terms, const sph::Settings& settings = {},
                          AtPause&& at_pause = {}, const WeakTubeRunOptions& options = {}) {
  WeakTubeRun run;
  run.name = name;
  sph::Particles<3> start = sph::make_weak_tube(setup);
  const sph::Vec<3> p0 = sph::total_momentum(start);
  const double e0 = sph::kinetic_energy(start) + sph::thermal_energy(start);
  const Stopwatch clock;
  sph::Simulation<Scene> sim(std::move(start), sph::weak_tube_box(), terms,
                             sph::IdealGas{setup.gamma}, settings);
  // A live progress line, no report at the end: the chapter prints its own table.
  ProgressDisplay display = ProgressDisplay::automatic();
  display.report = nullptr;
  Progress progress(options.t_end, name, display);
  for (int k = 0; k < options.pauses; ++k) {
    sim.run_until(options.t_end * (k + 1) / options.pauses, [&](const auto& s) {
      progress.update(s.steps() - 1, s.time(), s.last_limit().dt);
    });
    at_pause(sim, k);
  }
  progress.finish();
  run.seconds = clock.seconds();
  run.steps = sim.steps();
  run.particles = sim.particles();
  run.momentum_drift = momentum_drift(run.particles, p0);
  run.energy_change =
      std::abs(sph::kinetic_energy(run.particles) + sph::thermal_energy(run.particles) - e0) / e0;
  return run;
}

/// The Lagrangian reference for the weak tube of \p setup at \p t_end: planar, both states at
/// rest, \p zones_per_side zones of equal width on each side of the interface, free at both
/// ends (sph::Lagrangian1D).
inline sph::LagrangianProfile weak_tube_reference(const sph::WeakTubeSetup& setup,
                                                  int zones_per_side, double t_end = 20.0) {
  sph::LagrangianOptions options;
  options.gamma = setup.gamma;
  const double left = setup.density_left(), right = setup.density_right();
  auto tube = sph::Lagrangian1D::from_profile(
      sph::LagrangianGeometry::planar,
      sph::Lagrangian1D::uniform_edges({setup.z_left, setup.z_interface, setup.z_right},
                                       {zones_per_side, zones_per_side}),
      [&](double z) { return z < setup.z_interface ? left : right; }, [](double) { return 0.0; },
      [&](double) { return setup.u; }, options);
  tube.run_until(t_end);
  return tube.profile();
}

/// The Riemann problem of the weak tube's initial jump, centred on its interface: the
/// solution the tube follows until the waves from its free ends arrive.
inline sph::RiemannSolution weak_tube_riemann(const sph::WeakTubeSetup& setup) {
  const double P_left = (setup.gamma - 1) * setup.density_left() * setup.u;
  const double P_right = (setup.gamma - 1) * setup.density_right() * setup.u;
  return sph::RiemannSolution({setup.density_left(), 0, P_left},
                              {setup.density_right(), 0, P_right}, setup.gamma, setup.z_interface);
}

/// Mean absolute errors of \f$ v_z \f$, P and \f$ \rho \f$ against a profile.
struct WeakTubeErrors {
  double v = 0, pressure = 0, density = 0;
};

/// The \f$ L_1 \f$ errors (means over the particles) of \f$ v_z \f$, P and \f$ \rho \f$ of the
/// particles with \p z_low <= z <= \p z_high against the planar profile \p ref, interpolated at
/// each particle's z (app::interpolate: beyond the profile's ends, its end values).
inline WeakTubeErrors errors_along_z(const sph::Particles<3>& p, const sph::LagrangianProfile& ref,
                                     double z_low = -std::numeric_limits<double>::infinity(),
                                     double z_high = std::numeric_limits<double>::infinity()) {
  WeakTubeErrors e;
  long counted = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double z = p.position[i][2];
    if (z < z_low || z > z_high) continue;
    ++counted;
    e.v += std::abs(p.velocity[i][2] - interpolate(ref.radius, ref.velocity, z));
    e.pressure += std::abs(p.pressure[i] - interpolate(ref.radius, ref.pressure, z));
    e.density += std::abs(p.density[i] - interpolate(ref.radius, ref.density, z));
  }
  const double n = double(std::max(counted, 1L));
  return {e.v / n, e.pressure / n, e.density / n};
}

/// The kinetic energy of a planar profile, per unit of cross-section.
inline double planar_kinetic_energy(const sph::LagrangianProfile& ref) {
  double e = 0;
  for (std::size_t k = 0; k < ref.radius.size(); ++k) {
    const double dm = ref.density[k] * (ref.node_radius[k + 1] - ref.node_radius[k]);
    e += 0.5 * dm * ref.velocity[k] * ref.velocity[k];
  }
  return e;
}

/// The largest node speed of a profile.
inline double peak_node_speed(const sph::LagrangianProfile& ref) {
  double v = 0;
  for (double x : ref.node_velocity) v = std::max(v, std::abs(x));
  return v;
}

/// The share of the mass of a planar profile at time \p t in whose zones the density of
/// \p riemann differs from the profile's by more than \p tolerance (relative): how far the
/// flow has left the Riemann problem it started as.
inline double mass_fraction_off(const sph::LagrangianProfile& ref,
                                const sph::RiemannSolution& riemann, double t,
                                double tolerance = 0.01) {
  double off = 0, mass = 0;
  for (std::size_t k = 0; k < ref.radius.size(); ++k) {
    const double dm = ref.density[k] * (ref.node_radius[k + 1] - ref.node_radius[k]);
    mass += dm;
    if (std::abs(riemann.sample(ref.radius[k], t).density - ref.density[k]) >
        tolerance * ref.density[k])
      off += dm;
  }
  return off / mass;
}

}  // namespace app
