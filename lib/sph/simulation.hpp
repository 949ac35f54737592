#pragma once
/// \file
/// \brief A scene's physics chosen at compile time, and the step that runs only what it chose.
///
/// A scene names its dimension, kernel, equation of state, pressure form and viscosity as
/// template arguments of Physics; Simulation<Physics> then runs, every step,
///
///   smoothing lengths + neighbour list -> density -> equation of state -> forces -> kick/drift,
///
/// and nothing else: a scene without viscosity has no viscosity code, a polytropic gas no
/// energy equation, a 1D scene no 3D vectors.  Later chapters add terms by adding template
/// arguments, without touching the scenes that do not use them.
///
/// **Integrator.** Selhammar (1997) eq 8 is the leapfrog with velocities and energies at half
/// steps and positions at whole steps.  We write it in its kick-drift-kick form,
/// \f[ \mathbf v^{n+1/2} = \mathbf v^n + \tfrac12\delta t\,\mathbf a^n,\quad
///     \mathbf r^{n+1} = \mathbf r^n + \delta t\,\mathbf v^{n+1/2},\quad
///     \mathbf v^{n+1} = \mathbf v^{n+1/2} + \tfrac12\delta t\,\mathbf a^{n+1}, \f]
/// (and the same for u), which for a constant step produces exactly the same half-step
/// velocities and whole-step positions as eq 8, but also has v and u at whole steps (for
/// diagnostics and snapshots) and lets the step change from one step to the next.  The forces
/// at step n+1 need v and u there; they use the predicted
/// \f$ \mathbf v^{n+1/2} + \tfrac12\delta t\,\mathbf a^{n} \f$, as in GADGET-2 and SWIFT.
///
/// **Time step.** Selhammar eq 7:
/// \f$ \delta t = \min_i \varepsilon h_i / (|\mathbf v_i| + c_i + 1.2(\alpha c_i + \beta\mu_{i,\max})) \f$
/// with \f$ \varepsilon = 0.3 \f$, plus an acceleration limit
/// \f$ \varepsilon\sqrt{h_i/|\mathbf a_i|} \f$ and a cooling limit
/// \f$ \varepsilon\, u_i/|\dot u_i| \f$ where \f$ \dot u_i < 0 \f$.  As printed, eq 7 uses the particle's own
/// speed \f$ |\mathbf v_i| \f$, so the step depends on the frame of reference; the
/// signal-velocity alternative replaces \f$ |\mathbf v_i| \f$ by nothing (it is Galilean
/// invariant: only relative velocities, through \f$ \mu \f$, enter).  The limiting criterion
/// and particle of the last step are reported.

#include "sph/box.hpp"
#include "sph/density.hpp"
#include "sph/eos.hpp"
#include "sph/forces.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"
#include "sph/viscosity/none.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>

namespace sph {

/// The compile-time choices of a scene.
template <int Dim, class KernelT = Kernel<Dim>, class EosT = IdealGas, class ViscosityT = NoViscosity,
          class PressureFormT = PressureHernquistKatz>
struct Physics {
  static constexpr int D = Dim;
  using Kernel = KernelT;
  using Eos = EosT;
  using Viscosity = ViscosityT;
  using PressureForm = PressureFormT;
};

/// The run-time settings of a scene.
struct Settings {
  enum class TimestepRule { selhammar_eq7, signal_velocity };
  double courant = 0.3;  ///< epsilon of Selhammar eq 7
  TimestepRule timestep_rule = TimestepRule::selhammar_eq7;
  SmoothingLengthRule smoothing = SmoothingLengthRule::neighbour_number(64);
  DensityForm density = DensityForm::selhammar();
  long max_steps = 10'000'000;  ///< a run that needs more steps stops with an error
  double min_timestep = 1e-12;  ///< a step below this (relative to t_end) stops with an error
};

/// Which criterion set the last time step, and where.
struct TimestepLimit {
  std::string criterion;  ///< "Courant (eq 7)", "acceleration", "cooling", "output time"
  std::size_t particle = 0;
  double dt = 0;
};

template <class P>
class Simulation {
 public:
  static constexpr int D = P::D;
  using K = typename P::Kernel;
  using Eos = typename P::Eos;
  using Viscosity = typename P::Viscosity;
  static constexpr bool evolve_energy = Eos::evolves_energy;

  Simulation(Particles<D> particles, Box<D> box, Eos eos, Viscosity viscosity = {}, Settings settings = {})
      : particles_(std::move(particles)), box_(box), eos_(eos), viscosity_(viscosity), settings_(settings) {
    require(settings_.courant > 0 && settings_.courant < 1, "simulation: the Courant factor must lie in (0, 1)");
    box_.validate();
    particles_.validate();
    for (auto& x : particles_.position) x = box_.wrap(x);
    compute_accelerations();
  }

  // --- the passes of one evaluation, in order -------------------------------------------
  /// All passes at the current positions and (predicted) velocities.
  void compute_accelerations() {
    search_.update(particles_, box_, settings_.smoothing);
    scratch_.p_over_rho2.resize(particles_.size());
    positions_.assign(particles_.position);
    const PositionView<D> x = positions_.view(box_);
    compute_density<D, K>(particles_, search_.list(), x, settings_.density,
                          [this](std::size_t i) { equation_of_state(i); });
    compute_forces<D, K, typename P::PressureForm, Viscosity, evolve_energy>(particles_, search_.list(), x,
                                                                            viscosity_, scratch_);
    check_finite_forces();
  }

  /// The equation-of-state pass for one particle: P_i, c_i and P_i/rho_i^2 from rho_i and u_i
  /// (run inside the density loop, right after rho_i).
  void equation_of_state(std::size_t i) {
    auto& p = particles_;
    p.pressure[i] = eos_.pressure(p.density[i], p.internal_energy[i]);
    p.sound_speed[i] = eos_.sound_speed(p.density[i], p.internal_energy[i]);
    scratch_.p_over_rho2[i] = p.pressure[i] / (p.density[i] * p.density[i]);
  }

  // --- time stepping ------------------------------------------------------------------------
  /// The time step allowed by every criterion now (without the output-time clamp).
  TimestepLimit allowed_timestep() const {
    const auto& p = particles_;
    const std::size_t n = p.size();
    // Each chunk of particles finds its smallest step, then the chunks are compared in order
    // (a tie goes to the lower index): the same answer for any number of threads.
    constexpr std::size_t chunk = 4096;
    constexpr const char* criteria[] = {"none", "Courant (eq 7)", "acceleration", "cooling"};
    struct Best {
      double dt = std::numeric_limits<double>::infinity();
      std::size_t particle = 0;
      int criterion = 0;
    };
    std::vector<Best> best((n + chunk - 1) / chunk);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t c = 0; c < best.size(); ++c) {
      Best b;
      for (std::size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) {
        const double h = p.smoothing_length[i];
        double signal = p.sound_speed[i] + viscosity_.signal_term(p.sound_speed[i], scratch_.max_mu[i]);
        if (settings_.timestep_rule == Settings::TimestepRule::selhammar_eq7) signal += p.velocity[i].norm();
        if (signal > 0) {
          const double dt = settings_.courant * h / signal;
          if (dt < b.dt) b = {dt, i, 1};
        }
        const double a = p.acceleration[i].norm();
        if (a > 0) {
          const double dt = settings_.courant * std::sqrt(h / a);
          if (dt < b.dt) b = {dt, i, 2};
        }
        // Cooling: an explicit step must not remove more than a fraction of u (without it, an
        // inviscid collision can drive u negative in one step; chapter 3).
        if constexpr (evolve_energy) {
          if (p.energy_rate[i] < 0 && p.internal_energy[i] > 0) {
            const double dt = settings_.courant * p.internal_energy[i] / -p.energy_rate[i];
            if (dt < b.dt) b = {dt, i, 3};
          }
        }
      }
      best[c] = b;
    }
    Best overall;
    for (const Best& b : best) {
      if (b.dt < overall.dt) overall = b;
    }
    return {criteria[overall.criterion], overall.particle, overall.dt};
  }

  /// One kick-drift-kick step of at most dt_max; returns the step taken.
  double step(double dt_max = std::numeric_limits<double>::infinity()) {
    TimestepLimit limit = allowed_timestep();
    if (dt_max < limit.dt) limit = {"output time", limit.particle, dt_max};
    require(std::isfinite(limit.dt) && limit.dt > 0,
            "time step: no finite positive step (all particles at rest with zero sound speed?)");
    const double dt = limit.dt;
    kick_drift_predict(dt);
    compute_accelerations();
    // The second half kick starts from the half-step values, not from the prediction.
    std::swap(particles_.velocity, velocity_half_);
    if constexpr (evolve_energy) std::swap(particles_.internal_energy, energy_half_);
    kick(0.5 * dt);
    check_energy("after the step");
    time_ += dt;
    ++steps_;
    last_limit_ = limit;
    return dt;
  }

  /// Advance to exactly t_end, calling on_step(*this) after every step.
  void run_until(double t_end, const std::function<void(const Simulation&)>& on_step = {}) {
    require(std::isfinite(t_end), "run: the end time must be finite");
    const double span = t_end - time_;
    while (time_ < t_end) {
      if (steps_ >= settings_.max_steps) throw Error("run: more than " + std::to_string(settings_.max_steps) + " steps");
      const double remaining = t_end - time_;
      const double dt = step(remaining);
      if (dt < settings_.min_timestep * span && dt < remaining) {
        throw Error("time step collapsed to " + std::to_string(dt) + " at t = " + std::to_string(time_) +
                    " (limited by " + last_limit_.criterion + " at particle " + std::to_string(last_limit_.particle) + ")");
      }
      if (remaining - dt <= 1e-12 * std::abs(t_end)) time_ = t_end;  // hit the output time exactly
      if (on_step) on_step(*this);
    }
  }

  // --- access ------------------------------------------------------------------------------
  const Particles<D>& particles() const { return particles_; }
  Particles<D>& particles() { return particles_; }
  const NeighbourList<D>& neighbours() const { return search_.list(); }
  /// The neighbour search, e.g. for how often it could reuse its candidates.
  const NeighbourSearch<D, K>& neighbour_search() const { return search_; }
  const Box<D>& box() const { return box_; }
  const Eos& eos() const { return eos_; }
  const Viscosity& viscosity() const { return viscosity_; }
  const Settings& settings() const { return settings_; }
  double time() const { return time_; }
  long steps() const { return steps_; }
  const TimestepLimit& last_limit() const { return last_limit_; }

 private:
  void kick(double dt) {
    auto& p = particles_;
    const std::size_t n = p.size();
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      p.velocity[i] += dt * p.acceleration[i];
      if constexpr (evolve_energy) p.internal_energy[i] += dt * p.energy_rate[i];
    }
  }

  // The first half of a step in one pass over the particles: half kick to v^{n+1/2} (kept in
  // velocity_half_), drift, and the prediction v^{n+1/2} + a^n dt/2 that the forces at the end
  // of the step see (left in p.velocity); the same for u.
  void kick_drift_predict(double dt) {
    auto& p = particles_;
    const std::size_t n = p.size();
    velocity_half_.resize(n);
    if constexpr (evolve_energy) energy_half_.resize(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec<D> half_kick = 0.5 * dt * p.acceleration[i];
      velocity_half_[i] = p.velocity[i] + half_kick;
      p.position[i] = box_.wrap(p.position[i] + dt * velocity_half_[i]);
      p.velocity[i] = velocity_half_[i] + half_kick;
      if constexpr (evolve_energy) {
        const double half_heat = 0.5 * dt * p.energy_rate[i];
        energy_half_[i] = p.internal_energy[i] + half_heat;
        p.internal_energy[i] = energy_half_[i] + half_heat;
      }
    }
  }

  // A NaN or infinity must never travel on: stop and name the particle.
  void check_finite_forces() const {
    const auto& p = particles_;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!p.acceleration[i].allFinite() || !std::isfinite(p.energy_rate[i])) {
        throw Error("forces: particle " + std::to_string(i) + " at " + to_string<D>(p.position[i]) +
                    " has a non-finite acceleration or energy rate (rho = " + std::to_string(p.density[i]) +
                    ", P = " + std::to_string(p.pressure[i]) + ", h = " + std::to_string(p.smoothing_length[i]) + ")");
      }
    }
  }

  // The explicit energy equation can drive u below zero in a violent rarefaction when the step
  // is too long: stop and say so rather than continue with a negative pressure.
  void check_energy(const char* when) const {
    if constexpr (evolve_energy) {
      const auto& p = particles_;
      for (std::size_t i = 0; i < p.size(); ++i) {
        if (!(p.internal_energy[i] >= 0)) {
          throw Error(std::string("energy equation: ") + when + ", particle " + std::to_string(i) + " at " +
                      to_string<D>(p.position[i]) + " has internal energy " + std::to_string(p.internal_energy[i]) +
                      " at t = " + std::to_string(time_) + " (step too long for the cooling rate: lower the Courant factor)");
        }
      }
    }
  }

  Particles<D> particles_;
  Box<D> box_;
  Eos eos_;
  Viscosity viscosity_;
  Settings settings_;
  NeighbourSearch<D, K> search_;
  ForceScratch<D> scratch_;
  PositionArrays<D> positions_;  // the positions one array per axis, for the passes
  std::vector<Vec<D>> velocity_half_;  // v at the half step while the forces see the prediction
  std::vector<double> energy_half_;    // u likewise
  double time_ = 0;
  long steps_ = 0;
  TimestepLimit last_limit_;
};

}  // namespace sph
