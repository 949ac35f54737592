#pragma once
/// \file
/// \brief One run of the viscous ring: the scene, the accretion of particles that reach the
/// point mass, the snapshots at the output times, and what the run conserved.
///
/// The scene is a 2D gas with no pressure force -- only a viscosity term and the point mass
/// (sph::PointMass, the scene's external potential) -- with one smoothing length for all.  The
/// equation of state is an isothermal gas whose sound speed (`RingSettings::sound_speed`, small)
/// enters nothing but the Courant step: without a pressure term the gas has no pressure.
///
/// **Accretion.**  The ring's solution loses mass to the centre (eq 20 has an inflow at
/// R = 0), and a particle that follows it there would orbit ever faster with ever shorter steps.
/// So a particle that comes within the accretion radius \f$ r_\mathrm{acc} \f$ of the point mass
/// is taken out of the gas and its mass and angular momentum are added to the point mass's
/// account.  The simulation holds a fixed set of particles, so the run goes in short pieces
/// (`RingSettings::check_interval`) and, after a piece that brought any particle inside, starts
/// a new simulation from the others: all its state is in the particles, which the leapfrog
/// leaves synchronised at the end of each piece, so nothing else is lost.

#include "app/progress.hpp"
#include "app/stopwatch.hpp"
#include "sph/eos.hpp"
#include "sph/potential/point_mass.hpp"
#include "sph/setups/viscous_ring.hpp"
#include "sph/simulation.hpp"

#include <cmath>
#include <string>
#include <vector>

namespace app::ring {

/// A ring scene with the viscosity term `Term`.
template <class Term>
struct RingScene : sph::Scene<2> {
  using Eos = sph::Isothermal;
  using Terms = sph::Terms<Term>;
  using External = sph::PointMass<2>;
};

/// How a ring is run.
struct RingSettings {
  double accretion_radius = 0.1;  ///< \f$ r_\mathrm{acc} \f$
  double check_interval = 0.1;    ///< time between two looks for particles to accrete
  double sound_speed = 1e-3;      ///< of the isothermal gas: enters the Courant step only
  double courant = 0.3;
  bool progress = true;  ///< a progress line, and a report line at the end
};

/// The gas at one output time.
struct RingSnapshot {
  double tau = 0, t = 0;  ///< \f$ \tau \f$ and the time since \f$ \tau_0 \f$
  sph::Particles<2> particles;
  double accreted_mass = 0;  ///< by the point mass, so far
  double accreted_spin = 0;  ///< the angular momentum the accreted particles carried in
  long accreted = 0;         ///< particles accreted so far
};

/// What a run keeps.
struct RingRun {
  std::string name;
  std::vector<RingSnapshot> snapshots;  ///< at the output times (the first: the start)
  long steps = 0;
  double seconds = 0;
  std::string stopped;  ///< why the run ended early, if it did
};

/// The angular momentum \f$ \sum_i m_i (\mathbf x_i \times \mathbf v_i) \f$ of the gas.
inline double angular_momentum(const sph::Particles<2>& p) {
  double l = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    l += p.mass[i] * (p.position[i][0] * p.velocity[i][1] - p.position[i][1] * p.velocity[i][0]);
  return l;
}

/// Runs the ring \p disc with the viscosity term \p term and records it at each \f$ \tau \f$ of
/// \p taus (increasing, after the disc's \f$ \tau_0 \f$).  A stop by the simulation (sph::Error)
/// is kept in RingRun::stopped with what was recorded.
template <class Term>
RingRun run_ring(const std::string& name, const sph::setups::ViscousRingDisc& disc,
                 const Term& term, const std::vector<double>& taus, const RingSettings& rs = {}) {
  using Scene = RingScene<Term>;
  RingRun run;
  run.name = name;
  const Stopwatch clock;
  sph::Settings settings;
  settings.smoothing = sph::SmoothingLengthRule::fixed();
  settings.courant = rs.courant;
  const sph::PointMass<2> star(disc.G, disc.M);
  sph::Particles<2> gas = sph::setups::make_viscous_ring(disc);
  RingSnapshot account{disc.tau0, 0.0, {}, 0, 0, 0};
  const double t_end = disc.ring.time(taus.back() - disc.tau0);
  Progress progress(t_end, name, rs.progress ? ProgressDisplay::automatic() : ProgressDisplay{});
  double t = 0;        // since tau0
  long steps_now = 0;  // the steps of all pieces so far, for a run that stops in a piece
  /// A snapshot is the gas with the point mass's account so far.
  const auto record = [&](const sph::Particles<2>& p) {
    RingSnapshot s = account;
    s.t = t;
    s.tau = disc.tau0 + disc.ring.tau(t);
    s.particles = p;
    run.snapshots.push_back(std::move(s));
  };
  /// The run: one simulation per stretch between two accretions, each advanced in pieces
  /// of `check_interval` (or to the next output time), after each of which the particles
  /// are searched for one inside the accretion radius.
  try {
    std::size_t next = 0;
    while (next < taus.size()) {
      sph::Simulation<Scene> sim(gas, sph::Box<2>::open(), sph::Isothermal(rs.sound_speed), term,
                                 star, settings);
      // (the start is recorded from the first simulation, which has summed the densities)
      if (next == 0 && taus.front() <= disc.tau0 + 1e-12) {
        record(sim.particles());
        next = 1;
      }
      const double t0 = t;
      bool accreting = false;
      while (next < taus.size() && !accreting) {
        const double t_out = disc.ring.time(taus[next] - disc.tau0);
        const double t_piece = std::min(t_out, t + rs.check_interval);
        sim.run_until(t_piece - t0, [&](const auto& s) {
          steps_now = run.steps + s.steps();
          progress.update(steps_now - 1, t0 + s.time(), s.last_limit().dt);
        });
        t = t0 + sim.time();
        const auto& p = sim.particles();
        for (std::size_t i = 0; i < p.size() && !accreting; ++i)
          accreting = p.position[i].norm() < rs.accretion_radius;
        if (t >= t_out - 1e-12 * t_out) {
          record(p);
          ++next;
        }
      }
      run.steps += sim.steps();
      gas = sim.particles();
      if (accreting) {
        /// The accretion: the particles inside \f$ r_\mathrm{acc} \f$ leave the gas, and
        /// their mass and angular momentum go to the point mass's account.
        sph::Particles<2> kept;
        for (std::size_t i = 0; i < gas.size(); ++i) {
          const sph::Vec<2>& x = gas.position[i];
          if (x.norm() < rs.accretion_radius) {
            account.accreted_mass += gas.mass[i];
            account.accreted_spin +=
                gas.mass[i] * (x[0] * gas.velocity[i][1] - x[1] * gas.velocity[i][0]);
            ++account.accreted;
          } else {
            kept.add(x, gas.velocity[i], gas.mass[i], 0.0, gas.smoothing_length[i]);
          }
        }
        gas = std::move(kept);
      }
    }
  } catch (const sph::Error& e) {
    run.stopped = e.what();
    run.steps = steps_now;
  }
  progress.finish();
  run.seconds = clock.seconds();
  return run;
}

}  // namespace app::ring
