#pragma once
/// \file
/// \brief The kick-drift-kick leapfrog with individual time steps: each particle takes the
/// longest step its own limits allow, in power-of-two levels (a "block" scheme).
///
/// **Why.**  With one step for all, every particle moves with the step of the most demanding
/// one.  In the Evrard collapse the hot, dense centre needs steps ten to thirty times shorter
/// than the cold gas still falling in, yet the whole sphere is updated with them.  Giving each
/// particle its own step saves the updates the outer gas does not need (chapter 6 measures how
/// many: about half).
///
/// **The levels.**  Time is cut into blocks.  A block of length T is divided into
/// \f$ 2^{K} \f$ ticks, and a particle's step is a power of two of ticks,
/// \f$ T/2^k \f$: the longest such step not above the step its own limits allow (the
/// criteria of simulation.hpp, evaluated for that particle alone).  A step of length L may
/// start only at a multiple of L, so the levels nest: whenever a long step ends, the shorter
/// ones end with it, and at the end of the block all particles end together.  There the state
/// is synchronised -- every particle's v, u and acceleration belong to the same moment -- and
/// a new block starts with T the longest step any particle allows (or the time left to the
/// next output).  This is the arrangement of GADGET-2 (Springel 2005) and SWIFT.
///
/// **One step.**  At a moment t some particles start a step: the *active* ones, whose last
/// step ended at t.  Each gets its length L and its opening half kick,
/// \f$ \mathbf v_i^{1/2} = \mathbf v_i + \tfrac12 L\,\mathbf a_i \f$ (and u likewise).  The next
/// moment t' is the earliest end of any particle's step.  Every particle drifts to t' with its
/// half-step velocity -- the drift is cheap and the neighbour search needs everyone's
/// position -- and every particle's v and u are *predicted* at t' from its half-step values
/// and its last rates, \f$ \mathbf v_i(t') = \mathbf v_i^{1/2} + \mathbf a_i\,(t' - t_i - L_i/2)
/// \f$ (as GADGET-2 does; for a particle whose step ends at t' this is the leapfrog's own
/// prediction).  Then the evaluation, only for the particles whose step ends at t'
/// (Simulation::evaluate with an ActiveSet): their smoothing lengths and neighbours, densities,
/// forces, gravity and per-particle terms; the others keep theirs from their last step, and
/// the active particles read them.  These get their closing half kick with the new
/// accelerations.  With every particle on one level this is the leapfrog of integrators.hpp,
/// the same to round-off.
///
/// **The limiter.**  A particle on a long step does not notice that a shock has reached it
/// until its step ends: by then the shock has crossed it.  Saitoh & Makino (2009) showed that
/// block steps then fail badly in strong shocks (their point-explosion test), and that it is
/// enough to keep every particle's step within a factor f (4) of its neighbours'.  Here
///  1. a particle that starts a step takes at most f times the shortest step among its
///     neighbours -- those in mid-step with their steps, those starting with it with theirs,
///     which this rule may itself shorten, so it is applied until no length changes; and
///  2. when a particle starts a step shorter than 1/f of a neighbour's that is in mid-step,
///     that neighbour's step is cut short, to end with the first step of the particle.  Its
///     opening kick was given for the longer step, so the excess,
///     \f$ \tfrac12(L - L')\,\mathbf a \f$, is taken back from its half-step velocity (and u), and
///     the drift it already made with the excess is taken back from its position (after
///     Durier & Dalla Vecchia 2012, who showed that without such corrections energy is not
///     conserved).  What a term did to v at that kick (`with_kick`) is left as it was.
///
/// **What it costs, and what it breaks.**  Each step still drifts and predicts every particle,
/// checks every particle's candidates for neighbours (NeighbourSearch::update) and builds the
/// tree from all; the smoothing lengths, lists, densities, forces and the tree walk are paid
/// for the active particles only.  (Should the neighbour search fall back to a search of all --
/// a new box or rule -- it settles the h of the inactive particles too, while their densities
/// and pressures stay those of their last step until it ends.)  A pair whose particles are on
/// different levels is no longer evaluated at the same moment from both sides, so momentum is
/// conserved only to the accuracy of the integration, not to round-off, and energy only to the
/// order of the scheme.

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/integration/timestep_limit.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

namespace sph {

/// Kick-drift-kick leapfrog with individual time steps in power-of-two levels, with the time-step
/// limiter of Saitoh & Makino (2009).  See the file comment.
template <int D>
struct IndividualLeapfrog {
  static constexpr const char* name = "kick-drift-kick leapfrog, individual time steps";
  /// Simulation::step hands the whole step to this integrator (see simulation.hpp).
  static constexpr bool individual_steps = true;
  /// Ticks of a block: the shortest step is the block's length over 2^levels.
  static constexpr int levels = 40;
  /// A particle's step may be at most this many times its neighbours' (Saitoh & Makino 2009;
  /// 0: no limiter, to show what it does).
  double limiter = 4.0;
  /// Pay the works left unpaired by terms that change v at a kick (see Leapfrog).
  bool work_of_term_kicks = true;

  /// Whether every particle's step ends now (the state belongs to one moment).
  bool synchronised() const { return !in_block_; }
  /// The particles the last step evaluated (whose steps ended then), in increasing order.
  const std::vector<std::uint32_t>& active() const { return active_; }
  /// The length of particle i's present step (the last it began), in units of time.
  double step_length(std::size_t i) const { return static_cast<double>(length_.at(i)) * tick_; }

  /// Advance \p sim to the next moment at which some particles' steps end, no later than
  /// \p dt_max from now.  Returns that advance, with the criterion and particle of the shortest
  /// step begun here.
  template <class Sim>
  TimestepLimit step(Sim& sim, double dt_max) {
    static_assert(Sim::D == D, "the integrator's dimension must be the scene's");
    auto& p = sim.particles();
    const std::size_t n = p.size();
    require(limiter == 0 || (std::isfinite(limiter) && limiter >= 1),
            "individual time steps: the limiter must be 0 (off) or a finite factor of at least "
            "1 (got " +
                show(limiter) + ")");
    TimestepLimit shortest{"none", 0, std::numeric_limits<double>::infinity()};
    if (!in_block_) start_block(sim, dt_max);
    // (in absolute time: the block's end may lie an ulp past an output time it was cut to)
    const double block_end = block_start_ + block_;
    require(sim.time() + dt_max >= block_end - 1e-12 * std::abs(block_end),
            "individual time steps: an output time falls inside a block of steps (a block "
            "ends at " +
                show(block_end) +
                "); ask for output times only where the "
                "particles are synchronised");
    // The particles starting a step now: their lengths, the limiter, the opening kicks.
    choose_lengths(sim, shortest);
    if (limiter > 0) wake_neighbours(sim);
    open_kicks(sim);
    // The next moment at which some step ends, and everyone drifted and predicted to it.
    std::uint64_t next = std::numeric_limits<std::uint64_t>::max();
    for (std::size_t i = 0; i < n; ++i) next = std::min(next, start_[i] + length_[i]);
    drift_and_predict(sim, next);
    active_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (start_[i] + length_[i] == next) active_.push_back(static_cast<std::uint32_t>(i));
    }
    sim.evaluate(ActiveSet{&active_});
    close_kicks(sim);
    for (const std::uint32_t i : active_) start_[i] = next;
    const double before = sim.time();
    now_ = next;
    const double after = now_ == full_ ? block_end : block_start_ + tick_ * now_;
    if (now_ == full_) in_block_ = false;
    shortest.dt = after - before;
    return shortest;
  }

 private:
  // A new block: every particle is synchronised and starts a step at tick 0.
  template <class Sim>
  void start_block(Sim& sim, double dt_max) {
    const std::size_t n = sim.particles().size();
    double longest = 0;
    for (std::size_t i = 0; i < n; ++i) {
      const double dt = sim.particle_timestep(i).dt;
      if (std::isfinite(dt)) longest = std::max(longest, dt);
    }
    require(longest > 0,
            "individual time steps: no particle allows a finite positive step (all at rest "
            "with zero sound speed?)");
    block_ = std::min(longest, dt_max);
    block_start_ = sim.time();
    tick_ = std::ldexp(block_, -levels);
    now_ = 0;
    in_block_ = true;
    start_.assign(n, 0);
    length_.assign(n, 0);  // (0: starts a step now)
    v_half_.resize(n);
    u_half_.resize(n);
    changed_.resize(n, Vec<D>::Zero());
  }

  // The length of each particle that starts a step now: the longest power of two of ticks
  // within its own limit, within `limiter` times its neighbours' steps, and starting at a
  // multiple of itself.
  template <class Sim>
  void choose_lengths(Sim& sim, TimestepLimit& shortest) {
    const std::size_t n = sim.particles().size();
    starting_.clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (start_[i] == now_) starting_.push_back(static_cast<std::uint32_t>(i));
    }
    proposed_.assign(n, 0);
    new_length_.resize(starting_.size());
    std::string error;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t k = 0; k < starting_.size(); ++k) {
      const std::size_t i = starting_[k];
      const double dt =
          sim.moves(i) ? sim.particle_timestep(i).dt : std::numeric_limits<double>::infinity();
      proposed_[i] = dt > 0 ? nested(ticks_within(dt)) : 0;  // (a NaN step is no step)
      if (proposed_[i] == 0) {
#pragma omp critical(sph_individual_error)
        if (error.empty())
          error = "individual time steps: particle " + show(i) + " needs a step of " + show(dt) +
                  (dt > 0 ? ", below the shortest level of the block (" + show(tick_) + ")"
                          : " (a NaN or a non-positive value in its h, sound speed or "
                            "acceleration)");
      }
    }
    if (!error.empty()) throw Error(error);
    // The limiter, in sweeps until nothing changes: a neighbour in mid-step counts with its
    // step, one starting now with its length of the last sweep (at first what it wants).  A
    // particle shortened for its neighbour may shorten its own other neighbours in the next
    // sweep; lengths only fall, so the sweeps end, and each reads only the last one's lengths,
    // so the result does not depend on the number of threads.
    const auto& list = sim.neighbours();
    for (bool changed = true; changed;) {
      int shortened = 0;
#pragma omp parallel for schedule(static) reduction(| : shortened) if (n >= parallel_threshold)
      for (std::size_t k = 0; k < starting_.size(); ++k) {
        const std::size_t i = starting_[k];
        std::uint64_t length = proposed_[i];
        if (limiter > 0) {
          std::uint64_t least = full_;
          for (const auto& nb : list.of(i)) {
            const std::size_t j = nb.index;
            least = std::min(least, proposed_[j] > 0 ? proposed_[j] : length_[j]);
          }
          length = std::min(length, ticks_within(limiter * static_cast<double>(least) * tick_));
        }
        length = nested(length);
        new_length_[k] = length;
        shortened |= length != proposed_[i];
      }
      changed = limiter > 0 && shortened != 0;
      for (std::size_t k = 0; k < starting_.size(); ++k) proposed_[starting_[k]] = new_length_[k];
    }
    for (std::size_t k = 0; k < starting_.size(); ++k) {
      const std::size_t i = starting_[k];
      length_[i] = new_length_[k];
      start_[i] = now_;
      const double dt = static_cast<double>(length_[i]) * tick_;
      if (dt < shortest.dt) {
        const TimestepLimit own = sim.particle_timestep(i);
        shortest = {dt < own.dt * 0.5 ? "neighbour's step (limiter)" : own.criterion, i, dt};
      }
    }
  }

  // The longest step of at most `length` ticks that starts now (the levels nest: a step of
  // length L starts at a multiple of L).
  std::uint64_t nested(std::uint64_t length) const {
    while (length > 0 && now_ % length != 0) length /= 2;
    return length;
  }

  // The longest power of two of ticks, at most a whole block, not longer than dt (0 if dt is
  // shorter than one tick).
  std::uint64_t ticks_within(double dt) const {
    const std::uint64_t full = full_;
    if (!(dt < static_cast<double>(full) * tick_)) return full;
    const double ticks = dt / tick_;
    if (!(ticks >= 1)) return 0;
    return std::uint64_t{1} << static_cast<int>(std::floor(std::log2(ticks)));
  }

  // Cut short the steps of particles in mid-step that are more than `limiter` times longer than
  // a neighbour's new one (see the file comment): each such particle's step now ends with the
  // first step of its shortest new neighbour, and the excess of its opening kick and the drift
  // it made with it are taken back.
  template <class Sim>
  void wake_neighbours(Sim& sim) {
    auto& p = sim.particles();
    const std::size_t n = p.size();
    const auto& list = sim.neighbours();
    constexpr bool energy = Sim::evolve_energy;
    // The shortest new step among each particle's neighbours that start now (the lists of the
    // particles that start now are those of their last evaluation, which just ended their
    // steps; pairs are listed from both sides).
    least_.assign(n, std::numeric_limits<std::uint64_t>::max());
    for (const std::uint32_t i : starting_) {
      for (const auto& nb : list.of(i)) {
        std::uint64_t& least = least_[nb.index];
        least = std::min(least, length_[i]);
      }
    }
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t j = 0; j < n; ++j) {
      if (start_[j] == now_ || !sim.moves(j)) continue;  // (starting now, or never moving)
      const std::uint64_t least = least_[j];
      if (!(limiter * static_cast<double>(least) < static_cast<double>(length_[j]))) continue;
      const std::uint64_t end = now_ + least;
      if (end >= start_[j] + length_[j]) continue;
      const double excess = 0.5 * static_cast<double>(start_[j] + length_[j] - end) * tick_;
      const double drifted = static_cast<double>(now_ - start_[j]) * tick_;
      v_half_[j] -= excess * p.acceleration[j];
      if constexpr (energy) u_half_[j] -= excess * p.energy_rate[j];
      p.position[j] -= drifted * excess * p.acceleration[j];
      sim.drifted(j, v_half_[j]);
      length_[j] = end - start_[j];
    }
  }

  // The opening half kick of every particle that starts a step now (Leapfrog's, with its own
  // step).
  template <class Sim>
  void open_kicks(Sim& sim) {
    auto& p = sim.particles();
    constexpr bool energy = Sim::evolve_energy;
    const std::size_t n = p.size();
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t k = 0; k < starting_.size(); ++k) {
      const std::size_t i = starting_[k];
      if (!sim.moves(i)) {
        v_half_[i] = p.velocity[i];
        if constexpr (energy) u_half_[i] = p.internal_energy[i];
        continue;
      }
      const double dt = static_cast<double>(length_[i]) * tick_;
      v_half_[i] = p.velocity[i] + 0.5 * dt * p.acceleration[i];
      if constexpr (energy) {
        u_half_[i] = p.internal_energy[i] + 0.5 * dt * p.energy_rate[i];
        if constexpr (Sim::kicks_terms) {
          const Vec<D> kicked = v_half_[i];
          sim.kicked(i, 0.5 * dt, p.velocity[i], v_half_[i], u_half_[i]);
          if (work_of_term_kicks) {
            const Vec<D>& hydro = sim.hydro_acceleration(i);
            u_half_[i] +=
                0.5 * dt *
                ((v_half_[i] - kicked).dot(p.acceleration[i] - hydro) - changed_[i].dot(hydro));
          }
        }
      } else if constexpr (Sim::kicks_terms) {
        double no_energy = 0;
        sim.kicked(i, 0.5 * dt, p.velocity[i], v_half_[i], no_energy);
      }
    }
  }

  // Every particle drifted from now to `next` with its half-step velocity, and its v and u
  // predicted there from its half-step values and its last rates.
  template <class Sim>
  void drift_and_predict(Sim& sim, std::uint64_t next) {
    auto& p = sim.particles();
    constexpr bool energy = Sim::evolve_energy;
    const std::size_t n = p.size();
    const double span = static_cast<double>(next - now_) * tick_;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) {
      if (!sim.moves(i)) continue;
      p.position[i] += span * v_half_[i];
      sim.drifted(i, v_half_[i]);
      // (from the middle of the particle's step to `next`: half its step at its end)
      const double ahead =
          (static_cast<double>(next - start_[i]) - 0.5 * static_cast<double>(length_[i])) * tick_;
      p.velocity[i] = v_half_[i] + ahead * p.acceleration[i];
      if constexpr (energy) p.internal_energy[i] = u_half_[i] + ahead * p.energy_rate[i];
    }
  }

  // The closing half kick of the particles whose step ends now, with their new rates.
  template <class Sim>
  void close_kicks(Sim& sim) {
    auto& p = sim.particles();
    constexpr bool energy = Sim::evolve_energy;
    const std::size_t n = p.size();
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t k = 0; k < active_.size(); ++k) {
      const std::size_t i = active_[k];
      if (!sim.moves(i)) continue;
      const double dt = static_cast<double>(length_[i]) * tick_;
      p.velocity[i] = v_half_[i] + 0.5 * dt * p.acceleration[i];
      if constexpr (energy) p.internal_energy[i] = u_half_[i] + 0.5 * dt * p.energy_rate[i];
      if constexpr (Sim::kicks_terms) {
        double no_energy = 0;
        const Vec<D> kicked = p.velocity[i];
        sim.kicked(i, 0.5 * dt, v_half_[i], p.velocity[i],
                   energy ? p.internal_energy[i] : no_energy);
        if constexpr (energy) changed_[i] = p.velocity[i] - kicked;
      }
    }
  }

  static constexpr std::uint64_t full_ = std::uint64_t{1} << levels;
  bool in_block_ = false;
  double block_ = 0, block_start_ = 0, tick_ = 0;
  std::uint64_t now_ = 0;                      // ticks from the start of the block
  std::vector<std::uint64_t> start_, length_;  // each particle's present step, in ticks
  std::vector<std::uint64_t> proposed_;        // what a particle starting now asks for
  std::vector<std::uint64_t> new_length_;
  std::vector<std::uint64_t> least_;  // the shortest new step among a particle's neighbours
  std::vector<std::uint32_t> starting_, active_;
  std::vector<Vec<D>> v_half_;   // v at the middle of each particle's step
  std::vector<double> u_half_;   // u likewise
  std::vector<Vec<D>> changed_;  // what the terms changed v by at the last closing kick
};

}  // namespace sph
