#pragma once
/// \file
/// \brief Selhammar's homologous compression: app::run_homologous_sphere integrates the
/// sphere and records its energies after every step and its state at maximum compression;
/// app::homologous_sphere_reference does the same for the one-dimensional Lagrangian solution
/// in spherical shells.
///
/// The sphere (sph::make_homologous_sphere) falls inwards with \f$ \mathbf v = -2\mathbf r \f$,
/// without gravity or boundary.  Chapter 5 runs it with several viscosities, in the rest frame
/// and in a moving one (its step4_homologous_sphere() and galilean_boost() make the calls).
///
/// **Maximum compression** is the moment of the largest density of any particle (of the
/// central shell in the reference); the run keeps its particles there.  **A moving frame**: a
/// run given a boost adds it to every velocity at the start, and measures the kinetic energy
/// in the frame that moves with the boost, so that the energies of the two frames compare
/// directly.  After every step (and once at the start) the run hands the simulation to a
/// callable, so that the chapter can follow its terms as they act.
///
/// Chapter 5 runs its viscosities on the sphere; chapter 9 runs Watkins' bulk viscosity on it.

#include "app/particle_measures.hpp"
#include "app/progress.hpp"
#include "app/stopwatch.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/reference/lagrangian_1d.hpp"
#include "sph/setups/selhammar_problems.hpp"
#include "sph/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

namespace app {

/// What the chapter keeps of one run of the homologous sphere.
struct SphereRun {
  std::string name;
  std::vector<double> t, kinetic, thermal;  ///< after every step (kinetic: in the boost's frame)
  sph::Particles<3> at_maximum;             ///< at maximum compression (the largest density)
  double t_maximum = 0, peak_density = 0;   ///< its time, and that density
  double t_least_kinetic = 0;               ///< the time of the least kinetic energy
  double least_kinetic = INFINITY;
  double peak_thermal = 0;  ///< the largest thermal energy
  long steps = 0;
  double seconds = 0;         ///< wall time, the simulation's set-up included
  double momentum_drift = 0;  ///< \f$ |\mathbf P(t) - \mathbf P(0)| / \sum m|\mathbf v| \f$
  double energy_change = 0;   ///< \f$ |E(t) - E(0)|/E(0) \f$ between the first and last records
};

/// A callable that does nothing after a step.
struct NoProbe {
  template <class Sim>
  void operator()(const Sim&) const {}
};

/// Runs the sphere of \p setup with the scene \p Scene (its terms \p terms, an ideal gas of the
/// set-up's \f$ \gamma \f$, the step of \p settings) to \p t_end, every velocity increased by
/// \p boost, with a progress line named \p name.  After every step, and once at the start, it
/// records the energies and calls `probe(simulation)`.
template <class Scene, class Probe = NoProbe>
SphereRun run_homologous_sphere(const std::string& name, const sph::HomologousSphereSetup& setup,
                                const typename Scene::Terms& terms, double t_end,
                                const sph::Vec<3>& boost = sph::Vec<3>::Zero(),
                                const sph::Settings& settings = {}, Probe&& probe = {}) {
  SphereRun run;
  run.name = name;
  sph::Particles<3> start = sph::make_homologous_sphere(setup);
  for (auto& v : start.velocity) v += boost;
  const sph::Vec<3> p0 = sph::total_momentum(start);
  const Stopwatch clock;
  sph::Simulation<Scene> sim(std::move(start), sph::Box<3>::open(), terms,
                             sph::IdealGas{setup.gamma}, settings);
  /// The record of one step.  The particles are copied whenever the largest density rises, so
  /// the copy that remains is the state at maximum compression, whenever in the run that comes;
  /// the probe is called last, on the step just recorded.
  const auto record = [&](const sph::Simulation<Scene>& s) {
    // The energies, the kinetic one in the boost's frame.
    const auto& p = s.particles();
    double kinetic = 0;
    for (std::size_t i = 0; i < p.size(); ++i)
      kinetic += 0.5 * p.mass[i] * (p.velocity[i] - boost).squaredNorm();
    run.t.push_back(s.time());
    run.kinetic.push_back(kinetic);
    run.thermal.push_back(sph::thermal_energy(p));
    run.peak_thermal = std::max(run.peak_thermal, run.thermal.back());
    if (kinetic <= run.least_kinetic) {
      run.least_kinetic = kinetic;
      run.t_least_kinetic = s.time();
    }
    // Maximum compression: the largest density.
    const double rho = *std::max_element(p.density.begin(), p.density.end());
    if (rho > run.peak_density) {
      run.peak_density = rho;
      run.t_maximum = s.time();
      run.at_maximum = p;
    }
    probe(s);
  };
  /// The run: one record at the start, so that the energy change is measured from the initial
  /// state, then one after every step.  The momentum drift is measured against the boosted
  /// start, so the boost by itself is no drift.
  record(sim);
  ProgressDisplay display = ProgressDisplay::automatic();
  display.report = nullptr;
  Progress progress(t_end, name, display);
  sim.run_until(t_end, [&](const auto& s) {
    record(s);
    progress.update(s.steps() - 1, s.time(), s.last_limit().dt);
  });
  progress.finish();
  run.seconds = clock.seconds();
  run.steps = sim.steps();
  run.momentum_drift = momentum_drift(sim.particles(), p0);
  const double e0 = run.kinetic.front() + run.thermal.front();
  run.energy_change = std::abs(run.kinetic.back() + run.thermal.back() - e0) / e0;
  return run;
}

/// The reference's record: energies after every step, and its state at maximum compression.
struct SphereReference {
  std::vector<double> t, kinetic, thermal;
  double t_maximum = 0, peak_density = 0, t_least_kinetic = 0, peak_thermal = 0;
  double r90_at_maximum = 0;  ///< the radius holding 90 % of the mass at maximum compression
};

/// The Lagrangian sphere of \p setup at t = 0: \p zones shells of equal mass, the centre fixed,
/// the edge free, \f$ v = -v_0 r/R \f$, and a viscosity with the homologous limiter
/// (sph::LagrangianViscosity::homologous_limiter), which does not heat a self-similar
/// compression.
inline sph::Lagrangian1D homologous_sphere_lagrangian(const sph::HomologousSphereSetup& setup,
                                                      int zones) {
  sph::LagrangianOptions options;
  options.gamma = setup.gamma;
  options.left = sph::LagrangianEnd::centre;
  options.viscosity.homologous_limiter = true;
  const double rho0 = setup.density();
  const auto rho = [rho0](double) { return rho0; };
  return sph::Lagrangian1D::from_profile(
      sph::LagrangianGeometry::spherical,
      sph::Lagrangian1D::equal_mass_edges(sph::LagrangianGeometry::spherical, 0, setup.radius,
                                          zones, rho),
      rho, [&](double r) { return -setup.v0 * r / setup.radius; }, [&](double) { return setup.u; },
      options);
}

/// The radius of the first zone centre of \p prof with at least \p mass inside it (the outer
/// node past the last zone).
inline double radius_of_mass(const sph::LagrangianProfile& prof, double mass) {
  for (std::size_t k = 0; k < prof.radius.size(); ++k) {
    if (prof.mass_coordinate[k] >= mass) return prof.radius[k];
  }
  return prof.node_radius.back();
}

/// Runs the Lagrangian sphere of \p setup (\p zones shells) to \p t_end and returns its record.
inline SphereReference homologous_sphere_reference(const sph::HomologousSphereSetup& setup,
                                                   int zones, double t_end) {
  sph::Lagrangian1D gas = homologous_sphere_lagrangian(setup, zones);
  SphereReference ref;
  double least = INFINITY;
  const auto record = [&](const sph::Lagrangian1D& g) {
    ref.t.push_back(g.time());
    ref.kinetic.push_back(g.kinetic_energy());
    ref.thermal.push_back(g.thermal_energy());
    ref.peak_thermal = std::max(ref.peak_thermal, ref.thermal.back());
    if (g.kinetic_energy() < least) {
      least = g.kinetic_energy();
      ref.t_least_kinetic = g.time();
    }
    if (g.density(0) > ref.peak_density) {
      ref.peak_density = g.density(0);
      ref.t_maximum = g.time();
      ref.r90_at_maximum = radius_of_mass(g.profile(), 0.9 * setup.mass);
    }
  };
  record(gas);
  gas.run_until(t_end, record);
  return ref;
}

/// The Lagrangian sphere's profile at time \p t.
inline sph::LagrangianProfile homologous_sphere_profile(const sph::HomologousSphereSetup& setup,
                                                        int zones, double t) {
  sph::Lagrangian1D gas = homologous_sphere_lagrangian(setup, zones);
  gas.run_until(t);
  return gas.profile();
}

}  // namespace app
