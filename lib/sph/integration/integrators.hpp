#pragma once
/// \file
/// \brief The time integrators: the leapfrog of Selhammar (1997) and the predictor-corrector
/// of Watkins et al. (1996), both around one evaluation of the accelerations per step.
///
/// An integrator is a policy the scene names.  It owns the buffers it needs and advances the
/// particles by one step dt through the simulation's interface for integrators:
/// `particles()`, `moves(i)` (fixed boundary particles do not), `drifted(i, v)` (wrap into the
/// box, apply the boundaries' constraint to the position and to v, the velocity that carries on),
/// `kicked(i, dt, v_before, v, u)` (the terms' own updates of v and u at a kick, when
/// `Sim::kicks_terms`) and `evaluate()` (every pass of the step at the current state).  Both
/// integrators evaluate the accelerations once per step, so they cost the same.

#include "sph/dimension.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <vector>

namespace sph {

/// The kick-drift-kick leapfrog.  Selhammar (1997) eq 8 is the leapfrog with velocities and
/// energies at half steps and positions at whole steps; in its kick-drift-kick form
/// \f[ \mathbf v^{n+1/2} = \mathbf v^n + \tfrac12\delta t\,\mathbf a^n,\quad
///     \mathbf r^{n+1} = \mathbf r^n + \delta t\,\mathbf v^{n+1/2},\quad
///     \mathbf v^{n+1} = \mathbf v^{n+1/2} + \tfrac12\delta t\,\mathbf a^{n+1}, \f]
/// (and the same for u) it produces, for a constant step, exactly the same half-step
/// velocities and whole-step positions as eq 8, but also has v and u at whole steps (for
/// diagnostics and snapshots) and lets the step change from one step to the next.  The forces
/// at step n+1 need v and u there; they use the predicted
/// \f$ \mathbf v^{n+1/2} + \tfrac12\delta t\,\mathbf a^{n} \f$, as in GADGET-2 and SWIFT.  For
/// forces that depend on positions only it is symplectic: energy errors stay bounded, and a
/// central force conserves angular momentum to round-off.
///
/// <b>Terms that change v at a kick</b> (`with_kick`, such as the exact relaxation of
/// Selhammar's collective term) take kinetic energy and give it to u exactly, particle by
/// particle.  Two other works are then left unpaired, each of first order in the step, unless
/// the leapfrog pays them:
///  - the pair forces' heating \f$ \dot u_i \f$ was computed at the last evaluation with the
///    velocities before the terms changed them by \f$ \delta\mathbf v_i \f$ at the closing kick;
///    the kinetic energy the same forces give at the next opening kick counts the velocity
///    after.  The difference,
///    \f$ m_i\,\delta\mathbf v_i\cdot\mathbf a^{\rm hydro}_i\,\delta t/2 \f$ summed over the
///    particles, is what the pair forces' own energy equation
///    (\f$ \sum_i m_i \dot u_i = -\sum_i m_i \mathbf v_i\cdot\mathbf a^{\rm hydro}_i \f$) did not
///    see; it is taken from \f$ u_i \f$.
///  - gravity and the external potential gave kinetic energy at the opening kick to the velocity
///    that the terms then change by \f$ \delta\mathbf v'_i \f$, before the drift; the potential
///    energy changes with the velocity after the change.  Their work on the change,
///    \f$ m_i\,\delta\mathbf v'_i\cdot\mathbf a^{\rm body}_i\,\delta t/2 \f$, is given to
///    \f$ u_i \f$.
/// With both paid (`work_of_term_kicks`, the default) the total energy is conserved to the
/// leapfrog's second order again; without them (the form of earlier versions, kept to show the
/// difference) the error is of first order in the step.  The predictor-corrector does not pay
/// them: no scene pairs it with a term that changes v at a kick.
template <int D>
struct Leapfrog {
  static constexpr const char* name = "kick-drift-kick leapfrog (Selhammar eq 8)";
  /// Pay the works left unpaired by terms that change v at a kick (see above).
  bool work_of_term_kicks = true;

  template <class Sim>
  void step(Sim& sim, double dt) {
    static_assert(Sim::D == D, "the integrator's dimension must be the scene's");
    constexpr bool energy = Sim::evolve_energy;
    auto& p = sim.particles();
    const std::size_t n = p.size();
    velocity_half_.resize(n);
    if constexpr (energy) energy_half_.resize(n);
    if constexpr (energy && Sim::kicks_terms) changed_.resize(n, Vec<D>::Zero());
      // The first half kick to v^{n+1/2} (kept in velocity_half_), the drift, and the prediction
      // v^{n+1/2} + a^n dt/2 that the forces at the end of the step see (left in p.velocity);
      // the same for u.  One pass over the particles.
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      if (!sim.moves(i)) {
        velocity_half_[i] = p.velocity[i];
        if constexpr (energy) energy_half_[i] = p.internal_energy[i];
        continue;
      }
      const Vec<D> half_kick = 0.5 * dt * p.acceleration[i];
      velocity_half_[i] = p.velocity[i] + half_kick;
      if constexpr (energy) {
        const double half_heat = 0.5 * dt * p.energy_rate[i];
        energy_half_[i] = p.internal_energy[i] + half_heat;
        if constexpr (Sim::kicks_terms) {
          const Vec<D> kicked = velocity_half_[i];
          sim.kicked(i, 0.5 * dt, p.velocity[i], velocity_half_[i], energy_half_[i]);
          if (work_of_term_kicks) {
            // (see the class note) the pair forces' work on what the terms changed v by at the
            // last closing kick, and the body forces' work on what they change it by now
            const Vec<D>& hydro = sim.hydro_acceleration(i);
            energy_half_[i] += 0.5 * dt *
                               ((velocity_half_[i] - kicked).dot(p.acceleration[i] - hydro) -
                                changed_[i].dot(hydro));
          }
        }
        p.internal_energy[i] = energy_half_[i] + half_heat;
      } else if constexpr (Sim::kicks_terms) {
        double no_energy = 0;
        sim.kicked(i, 0.5 * dt, p.velocity[i], velocity_half_[i], no_energy);
      }
      p.position[i] += dt * velocity_half_[i];
      sim.drifted(i, velocity_half_[i]);
      p.velocity[i] = velocity_half_[i] + half_kick;
    }
    sim.evaluate();
    // The second half kick starts from the half-step values, not from the prediction.
    std::swap(p.velocity, velocity_half_);
    if constexpr (energy) std::swap(p.internal_energy, energy_half_);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      if (!sim.moves(i)) continue;
      const Vec<D> before = p.velocity[i];
      p.velocity[i] += 0.5 * dt * p.acceleration[i];
      if constexpr (energy) p.internal_energy[i] += 0.5 * dt * p.energy_rate[i];
      if constexpr (Sim::kicks_terms) {
        double no_energy = 0;
        const Vec<D> kicked = p.velocity[i];
        sim.kicked(i, 0.5 * dt, before, p.velocity[i], energy ? p.internal_energy[i] : no_energy);
        if constexpr (energy) changed_[i] = p.velocity[i] - kicked;
      }
    }
  }

 private:
  std::vector<Vec<D>> velocity_half_;  // v at the half step while the forces see the prediction
  std::vector<double> energy_half_;    // u likewise
  std::vector<Vec<D>> changed_;        // what the terms changed v by at the last closing kick
};

/// A second-order predictor-corrector: the midpoint method, with one evaluation per step.
/// Watkins et al. (1996, Appendix A) integrate with "a second order predictor-corrector with a
/// constant timestep" and name no scheme; we use the midpoint form, with one evaluation a step:
/// \f[ \text{predict:}\quad \mathbf r^* = \mathbf r^n + \tfrac12\delta t\,\mathbf v^n,\quad
///     \mathbf v^* = \mathbf v^n + \tfrac12\delta t\,\mathbf a^{n-1/2},\quad
///     u^* = u^n + \tfrac12\delta t\,\dot u^{n-1/2}; \f]
/// \f[ \text{evaluate}\quad \mathbf a^{n+1/2} = \mathbf a(\mathbf r^*, \mathbf v^*, u^*); \f]
/// \f[ \text{correct:}\quad \mathbf v^{n+1} = \mathbf v^n + \delta t\,\mathbf a^{n+1/2},\quad
///     \mathbf r^{n+1} = \mathbf r^n
///       + \delta t\,(\mathbf v^n + \tfrac12\delta t\,\mathbf a^{n+1/2}),\quad
///     u^{n+1} = u^n + \delta t\,\dot u^{n+1/2}. \f]
/// The predictor uses the accelerations of the previous step's midpoint, which are
/// \f$ O(\delta t) \f$ off the ones at \f$ t^n \f$; the predicted state is then
/// \f$ O(\delta t^2) \f$ off the true midpoint, the midpoint accelerations \f$ O(\delta t^2) \f$
/// off, and the step's error \f$ O(\delta t^3) \f$: second order globally, with one evaluation
/// per step (tested on an orbit: halving the step quarters the error).  For forces that depend
/// on the positions only it is the drift-kick-drift leapfrog -- \f$ \mathbf r^* \f$ is a half
/// drift, \f$ \mathbf v^{n+1} \f$ a whole kick at \f$ \mathbf r^* \f$, and
/// \f$ \mathbf r^{n+1} = \mathbf r^* + \tfrac12\delta t\,\mathbf v^{n+1} \f$ the second half
/// drift -- so on an orbit it is symplectic too: its energy error stays bounded and a central
/// force conserves angular momentum to round-off (tests/sph/test_step_parts.cpp).  It differs
/// from the kick-drift-kick leapfrog only through \f$ \mathbf v^* \f$ and \f$ u^* \f$, where
/// the forces depend on velocities or internal energy.  After a step the particles'
/// accelerations are those of the midpoint \f$ t^{n+1/2} \f$.
template <int D>
struct PredictorCorrector {
  static constexpr const char* name = "midpoint predictor-corrector (Watkins et al. 1996)";

  template <class Sim>
  void step(Sim& sim, double dt) {
    static_assert(Sim::D == D, "the integrator's dimension must be the scene's");
    constexpr bool energy = Sim::evolve_energy;
    auto& p = sim.particles();
    const std::size_t n = p.size();
    position_.resize(n);
    velocity_.resize(n);
    if constexpr (energy) energy_.resize(n);
      // Predict the midpoint state (the start of the step kept aside).
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      position_[i] = p.position[i];
      velocity_[i] = p.velocity[i];
      if constexpr (energy) energy_[i] = p.internal_energy[i];
      if (!sim.moves(i)) continue;
      p.position[i] += 0.5 * dt * p.velocity[i];
      p.velocity[i] += 0.5 * dt * p.acceleration[i];
      if constexpr (energy) p.internal_energy[i] += 0.5 * dt * p.energy_rate[i];
      sim.drifted(i, p.velocity[i]);
    }
    sim.evaluate();
    // Correct from the start of the step with the midpoint's accelerations.
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      if (!sim.moves(i)) continue;
      const Vec<D> kick = dt * p.acceleration[i];
      p.velocity[i] = velocity_[i] + kick;
      if constexpr (energy) p.internal_energy[i] = energy_[i] + dt * p.energy_rate[i];
      if constexpr (Sim::kicks_terms) {
        double no_energy = 0;
        sim.kicked(i, dt, velocity_[i], p.velocity[i], energy ? p.internal_energy[i] : no_energy);
        // (a term may have changed the end velocity: the drift takes the mean of the two)
        p.position[i] = position_[i] + 0.5 * dt * (velocity_[i] + p.velocity[i]);
      } else {
        p.position[i] = position_[i] + dt * (velocity_[i] + 0.5 * kick);
      }
      sim.drifted(i, p.velocity[i]);
    }
  }

 private:
  std::vector<Vec<D>> position_, velocity_;  // the state at the start of the step
  std::vector<double> energy_;
};

}  // namespace sph
