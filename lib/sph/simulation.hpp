#pragma once
/// \file
/// \brief The step: one evaluation of every part a scene names, and the time step they allow.
///
/// Simulation<Scene> holds the particles, the box and the parts of the scene (scene.hpp), and
/// advances them with the scene's integrator.  Every integrator calls one evaluate(), which
/// runs, in order, only the passes the scene's parts need:
///
/// | pass | runs when | writes |
/// |:--|:--|:--|
/// | smoothing lengths + neighbour list | the scene has terms | h, neighbour count, the list |
/// | density (+ equation of state, + `after_density` hooks) | the scene has terms | rho, P, c, P/rho^2; rho-dot, div v, curl v if a term needs them |
/// | gradient (a second loop over the same list) | a term has a gradient pass | the terms' own fields |
/// | `before_force` hooks | a term has one | the terms' own fields |
/// | force | the scene has terms | a, du/dt, max mu; a term's force-pass sums, finished per particle |
/// | `after_force` hooks | a term has one | a, du/dt (per-particle terms) |
/// | self-gravity | Gravity is not NoGravity | a |
/// | external potential | External is not NoExternalPotential | a |
///
/// **Time step.**  The smallest of the limits the parts bring, over the moving particles:
/// the Courant criterion of Selhammar eq 7,
/// \f$ \delta t = \varepsilon h_i / (|\mathbf v_i| + c_i + \sum_\mathrm{terms} s_i) \f$ with
/// \f$ \varepsilon = 0.3 \f$ and \f$ s_i \f$ the terms' signal speeds (the Monaghan & Gingold
/// viscosity adds \f$ 1.2(\alpha c_i + \beta\mu_{i,\max}) \f$); an acceleration limit
/// \f$ \varepsilon\sqrt{h_i/|\mathbf a_i|} \f$; a cooling limit
/// \f$ \varepsilon\, u_i/|\dot u_i| \f$ where \f$ \dot u_i < 0 \f$; each term's own limit; and the
/// external potential's.  As printed, eq 7 uses the particle's own speed
/// \f$ |\mathbf v_i| \f$, so the step depends on the frame of reference.  The alternative a
/// scene may choose (Settings::TimestepRule::signal_velocity) is the signal velocity of
/// Monaghan (1997), which sees only relative velocities and is Galilean invariant:
/// \f[ \delta t = \varepsilon \min_i \frac{h_i}{\max_j v_{{\rm sig},ij}}, \qquad
///     v_{{\rm sig},ij} = c_i + c_j - \beta_{\rm sig}\, w_{ij}, \qquad
///     w_{ij} = \min(\mathbf v_{ij}\cdot\hat{\mathbf r}_{ij}, 0), \f]
/// the maximum over the pairs within the kernel's support (and the particle itself, \f$ 2c_i \f$),
/// kept by the force pass; the terms' signal speeds, which are their shares of eq 7, do not enter
/// it (their own limits do).  A scene may also fix the step (Watkins et al. integrate with a
/// constant one).  The limiting criterion and particle of the last step are reported.

#include "sph/box.hpp"
#include "sph/density.hpp"
#include "sph/fields.hpp"
#include "sph/forces.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/integration/timestep_limit.hpp"
#include "sph/neighbours.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"
#include "sph/scene.hpp"
#include "sph/setups/initial_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace sph {

/// The run-time settings of a scene.
struct Settings {
  /// Selhammar's eq 7, or the pair signal velocity of Monaghan (1997) (see the file comment).
  enum class TimestepRule { selhammar_eq7, signal_velocity };
  double courant = 0.3;  ///< epsilon of Selhammar eq 7 (or of the signal-velocity rule)
  TimestepRule timestep_rule = TimestepRule::selhammar_eq7;
  double signal_beta = 2.0;  ///< \f$ \beta_{\rm sig} \f$ of the signal-velocity rule
  SmoothingLengthRule smoothing = SmoothingLengthRule::neighbour_number(64);
  DensityForm density = DensityForm::selhammar();
  double fixed_timestep = 0;    ///< a constant step (Watkins et al.); 0: the limits decide
  long max_steps = 10'000'000;  ///< a run that needs more steps stops with an error
  double min_timestep = 1e-12;  ///< a step below this (relative to t_end) stops with an error
};

/// The particles, the box and the parts a scene S names, evaluated together: the passes of
/// one evaluation, the time step they allow, and the integrator's step.
template <class S>
class Simulation {
 public:
  using Scene = S;
  static constexpr int D = S::D;
  using K = typename S::Kernel;
  using Eos = typename S::Eos;
  using TermList = typename S::Terms;
  using Gravity = typename S::Gravity;
  using External = typename S::External;
  using Boundaries = typename S::Boundaries;
  using Integrator = typename S::Integrator;
  /// A scene with no terms has no hydrodynamics: no neighbour search, density or force pass
  /// (test particles in a potential, or pure N-body).
  static constexpr bool hydro = TermList::count > 0;
  static constexpr bool evolve_energy = hydro && Eos::evolves_energy;
  // An equation of state of the particle (sph::Adiabats): called with its index.
  static constexpr bool per_particle_eos = requires { requires Eos::per_particle; };
  static constexpr Needs needs = TermList::needs;
  static_assert(
      TermList::template all_recognised<D>,
      "Simulation: a term of the scene has no member the step recognises -- check its members' "
      "signatures against the table in sph/terms.hpp");
  static_assert(TermList::template slots_fit<D>);

  /// The particles, the box, and any of the scene's parts in any order, each by its type: the
  /// equation of state, a term, Settings, the gravity module, the external potential, the
  /// boundaries, the integrator.  Parts not given take their defaults.
  template <class... Parts>
  Simulation(Particles<D> particles, Box<D> box, const Parts&... parts)
      : particles_(std::move(particles)), box_(box) {
    (set(parts), ...);
    require(std::isfinite(settings_.courant) && settings_.courant > 0 && settings_.courant < 1,
            "simulation: the Courant factor must lie in (0, 1)");
    require(std::isfinite(settings_.fixed_timestep) && settings_.fixed_timestep >= 0,
            "simulation: the fixed time step must be positive (or 0 for the adaptive step)");
    require(std::isfinite(settings_.signal_beta) && settings_.signal_beta >= 0,
            "simulation: the signal velocity's beta must be non-negative");
    box_.validate();
    particles_.validate();
    if constexpr (hydro) require_distinct_particles();
    boundaries_.validate(particles_);
    if constexpr (per_particle_eos)
      require(eos_.K.size() == particles_.size(),
              "simulation: the equation of state has " + std::to_string(eos_.K.size()) +
                  " adiabats for " + std::to_string(particles_.size()) + " particles");
    for (auto& x : particles_.position) x = box_.wrap(x);
    terms_.for_each([n = particles_.size()](auto& t) {
      if constexpr (HasResize<std::decay_t<decltype(t)>>) t.resize(n);
    });
    evaluate();
  }

  // --- one evaluation: every pass the scene needs, at the current state --------------------
  /// All passes at the current positions and (predicted) velocities and energies.  With an
  /// ActiveSet (an integrator of individual time steps: the particles whose step ends now),
  /// every pass computes only the active particles, from the present positions and predicted
  /// velocities of all; the others keep their smoothing lengths, densities, pressures,
  /// accelerations and energy rates from the last time they were active, and the active ones
  /// read those (as in PHANTOM and GADGET-2, which predict them).
  void evaluate(ActiveSet active = {}) {
    evaluated_ = active.size(particles_.size());
    if constexpr (hydro) {
      // (a kick may have left a particle with negative energy: stop before it becomes a NaN)
      check_energy("after the kick, before the forces");
      search_.update(particles_, box_, settings_.smoothing, active);
      positions_.assign(particles_.position);
      velocities_.assign(particles_.velocity);
      fields_.p_over_rho2.resize(particles_.size());
      density_pass(active);
      if constexpr (TermList::template any_gradient_pass<D>) gradient_pass(active);
      if constexpr (TermList::template any_before_force<D>) before_force(active);
      if (pair_signal()) {
        compute_forces<D, K, TermList, evolve_energy, true>(particles_, search_.list(), view(),
                                                            terms_, fields_, settings_.signal_beta,
                                                            &force_sums_, active);
      } else {
        compute_forces<D, K, TermList, evolve_energy>(particles_, search_.list(), view(), terms_,
                                                      fields_, 0.0, &force_sums_, active);
      }
      if constexpr (TermList::template any_force_sum<D>) finish_force_sums(active);
      if constexpr (TermList::template any_after_force<D>) after_force(active);
      if constexpr (keeps_hydro_acceleration) {
        hydro_acceleration_.resize(particles_.size());
        for (std::size_t k = 0; k < evaluated_; ++k)
          hydro_acceleration_[active[k]] = particles_.acceleration[active[k]];
      }
    } else {
      for (std::size_t k = 0; k < evaluated_; ++k) particles_.acceleration[active[k]].setZero();
    }
    if constexpr (Gravity::active) gravity_.add_accelerations(particles_, box_, active);
    if constexpr (External::active) external_accelerations(active);
    if constexpr (requires { requires Boundaries::constrains_acceleration; }) {
      // (after every force: a NaN is kept, for the check below to name)
      for (std::size_t k = 0; k < evaluated_; ++k) {
        const std::size_t i = active[k];
        if (moves(i) && particles_.acceleration[i].allFinite())
          boundaries_.constrain_acceleration(particles_.acceleration[i]);
      }
    }
    check_finite_forces();
  }

  // --- time stepping ------------------------------------------------------------------------
  /// The time step allowed by every criterion now (without the output-time clamp).
  TimestepLimit allowed_timestep() const {
    if (settings_.fixed_timestep > 0) return {"fixed step", 0, settings_.fixed_timestep};
    const std::size_t n = particles_.size();
    // Each chunk of particles finds its smallest step, then the chunks are compared in order
    // (a tie goes to the lower index): the same answer for any number of threads.
    constexpr std::size_t chunk = 4096;
    std::vector<Limit> best((n + chunk - 1) / chunk);
    const ParticleView<D> in = view();
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t c = 0; c < best.size(); ++c) {
      for (std::size_t i = c * chunk; i < std::min(n, (c + 1) * chunk); ++i) {
        if (!moves(i)) continue;
        const Limit limit = particle_limit(i, in);
        if (limit.dt < best[c].dt) best[c] = limit;
      }
    }
    Limit overall;
    for (const Limit& b : best) {
      if (b.dt < overall.dt) overall = b;
    }
    return {overall.criterion, overall.particle, overall.dt};
  }

  /// The step each particle alone allows now: the smallest of the limits in the file comment
  /// for that particle (infinite for one that does not move or that no limit applies to).
  /// The global step is the least of them; a scheme of individual time steps would give each
  /// particle its own (chapter 6 measures what that would save).
  void particle_timesteps(std::vector<double>& dt) const {
    if (settings_.fixed_timestep > 0) {
      dt.assign(particles_.size(), settings_.fixed_timestep);
      return;
    }
    const std::size_t n = particles_.size();
    dt.resize(n);
    const ParticleView<D> in = view();
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i)
      dt[i] = moves(i) ? particle_limit(i, in).dt : std::numeric_limits<double>::infinity();
  }

  /// The step particle i alone allows now, and which criterion sets it (see particle_timesteps).
  TimestepLimit particle_timestep(std::size_t i) const {
    if (settings_.fixed_timestep > 0) return {"fixed step", i, settings_.fixed_timestep};
    if (!moves(i)) return {"none", i, std::numeric_limits<double>::infinity()};
    const Limit limit = particle_limit(i, view());
    return {limit.criterion, i, limit.dt};
  }

  /// Whether the scene's integrator gives each particle its own time step.
  static constexpr bool individual_steps = requires { requires Integrator::individual_steps; };

  /// One step of the scene's integrator, of at most dt_max; returns the step taken.  With
  /// individual time steps, one step is the advance to the next moment at which some
  /// particles' steps end (see individual_leapfrog.hpp).
  double step(double dt_max = std::numeric_limits<double>::infinity()) {
    TimestepLimit limit;
    if constexpr (individual_steps) {
      require(dt_max > 0, "time step: the step must be positive");
      limit = integrator_.step(*this, dt_max);
    } else {
      limit = allowed_timestep();
      if (dt_max < limit.dt) limit = {"output time", limit.particle, dt_max};
      require(std::isfinite(limit.dt) && limit.dt > 0,
              "time step: no finite positive step (all particles at rest with zero sound speed?)");
      integrator_.step(*this, limit.dt);
    }
    const double dt = limit.dt;
    if constexpr (Boundaries::has_constraint) {
      if (constraint_failed_ >= 0) {
        const auto i = static_cast<std::size_t>(constraint_failed_);
        throw Error("particle " + show(i) + ": " +
                    boundaries_.describe_failure(particles_.position[i]));
      }
    }
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
      if (steps_ >= settings_.max_steps)
        throw Error("run: more than " + show(settings_.max_steps) + " steps");
      const double remaining = t_end - time_;
      const double dt = step(remaining);
      if (dt < settings_.min_timestep * span && dt < remaining) {
        throw Error("time step collapsed to " + show(dt) + " at t = " + show(time_) +
                    " (limited by " + last_limit_.criterion + " at particle " +
                    show(last_limit_.particle) + ")");
      }
      if (remaining - dt <= 1e-12 * std::abs(t_end)) time_ = t_end;  // hit the output time exactly
      if (on_step) on_step(*this);
    }
  }

  // --- what an integrator may do (integrators.hpp) ------------------------------------------
  /// Whether particle i moves (fixed boundary particles do not).
  bool moves(std::size_t i) const { return Boundaries::moves(i, particles_); }
  /// After particle i's position changed: wrap it into the box, apply the boundaries'
  /// constraint to it and to `velocity`, the velocity it carries on with (the leapfrog's
  /// half-step velocity, the predictor-corrector's new one).
  void drifted(std::size_t i, Vec<D>& velocity) {
    particles_.position[i] = box_.wrap(particles_.position[i]);
    if constexpr (Boundaries::has_constraint) {
      if (!boundaries_.constrain(particles_.position[i], velocity)) {
#pragma omp critical(sph_constraint)
        if (constraint_failed_ < 0 || static_cast<long>(i) < constraint_failed_)
          constraint_failed_ = static_cast<long>(i);
      }
    }
  }
  /// Whether any term acts on the kicks (integrators call kicked() only then).
  static constexpr bool kicks_terms = TermList::template any_with_kick<D>;
  /// The acceleration of particle i by the force pass alone (the pair forces and the terms,
  /// without gravity and the external potential), at the last evaluation.  The leapfrog needs
  /// it when a term changes v at a kick: the pair forces' heating was computed with the
  /// velocities before that change, and the work they do on the change is owed to u (see
  /// Leapfrog).  Kept as a copy only in scenes whose terms act on kicks and that also have
  /// gravity or an external potential; otherwise it is the particle's acceleration.
  const Vec<D>& hydro_acceleration(std::size_t i) const {
    if constexpr (keeps_hydro_acceleration)
      return hydro_acceleration_[i];
    else
      return particles_.acceleration[i];
  }
  /// After particle i was kicked by dt from velocity v_before to v: the terms' own updates of
  /// v and u (u is a dummy when the gas does not evolve it).
  void kicked(std::size_t i, double dt, const Vec<D>& v_before, Vec<D>& v, double& u) {
    if constexpr (kicks_terms) {
      terms_.for_each([&](auto& t) {
        if constexpr (HasWithKick<std::decay_t<decltype(t)>, D>) t.with_kick(i, dt, v_before, v, u);
      });
    }
  }

  // --- access ------------------------------------------------------------------------------
  const Particles<D>& particles() const { return particles_; }
  Particles<D>& particles() { return particles_; }
  /// The neighbour list of the last evaluation (with individual time steps, only the particles
  /// it evaluated have one; the others' lists are empty).
  const NeighbourList<D>& neighbours() const { return search_.list(); }
  /// The neighbour search, e.g. for how often it could reuse its candidates.
  const NeighbourSearch<D, K>& neighbour_search() const { return search_; }
  const Box<D>& box() const { return box_; }
  const Eos& eos() const { return eos_; }
  const TermList& terms() const { return terms_; }
  /// Term T of the scene.
  template <class T>
  const T& term() const {
    return terms_.template get<T>();
  }
  const External& external() const { return external_; }
  const Gravity& gravity() const { return gravity_; }
  const Settings& settings() const { return settings_; }
  /// The fields only some scenes have (rho-dot, div v, curl v, ...): empty when not named.
  const DerivedFields<D>& fields() const { return fields_; }
  /// Every field as plain arrays, as the terms see them (valid until the next step).
  ParticleView<D> view() const {
    const auto& p = particles_;
    ParticleView<D> v;
    v.x = positions_.view(box_);
    for (int a = 0; a < D; ++a) v.v[a] = velocities_.axis(a);
    v.h = p.smoothing_length.data();
    v.m = p.mass.data();
    v.u = p.internal_energy.data();
    v.rho = p.density.data();
    v.pressure = p.pressure.data();
    v.c = p.sound_speed.data();
    v.p_over_rho2 = fields_.p_over_rho2.data();
    v.max_mu = fields_.max_mu.data();
    v.density_rate = fields_.density_rate.data();
    v.divergence = fields_.velocity_divergence.data();
    for (int a = 0; a < curl_components<D>; ++a) v.curl[a] = fields_.velocity_curl[a].data();
    v.kind = p.kind.data();
    return v;
  }
  /// The potential energy in the external potential and in self-gravity.
  double potential_energy() const {
    double e = 0;
    if constexpr (External::active) {
      for (std::size_t i = 0; i < particles_.size(); ++i)
        e += particles_.mass[i] * external_.potential(particles_.position[i]);
    }
    if constexpr (Gravity::active) e += gravity_.potential_energy(particles_, box_);
    return e;
  }
  double time() const { return time_; }
  long steps() const { return steps_; }
  /// How many particles the last evaluation computed (all but with individual time steps).
  std::size_t evaluated() const { return evaluated_; }
  /// Whether every particle's velocity, energy and acceleration belong to the present time:
  /// always with one step for all; with individual time steps, only where all their steps end
  /// together (between, a particle in mid-step carries predicted values).
  bool synchronised() const {
    if constexpr (individual_steps)
      return integrator_.synchronised();
    else
      return true;
  }
  const Integrator& integrator() const { return integrator_; }
  const TimestepLimit& last_limit() const { return last_limit_; }

 private:
  // Whether the time step is the signal-velocity rule, whose pair maximum the force pass keeps.
  bool pair_signal() const {
    return settings_.timestep_rule == Settings::TimestepRule::signal_velocity;
  }

  // The least step of particle i's criteria and which one sets it (allowed_timestep and
  // particle_timesteps; a name, not a string, on this per-particle path).
  struct Limit {
    double dt = std::numeric_limits<double>::infinity();
    std::size_t particle = 0;
    const char* criterion = "none";
    void consider(double step, const char* name) {
      if (step < dt) dt = step, criterion = name;
    }
  };
  Limit particle_limit(std::size_t i, const ParticleView<D>& in) const {
    const auto& p = particles_;
    Limit limit;
    limit.particle = i;
    if constexpr (hydro) {
      const double courant = settings_.courant;
      const double h = p.smoothing_length[i];
      if (pair_signal()) {
        const double signal = std::max(fields_.max_signal[i], 2.0 * p.sound_speed[i]);
        if (signal > 0) limit.consider(courant * h / signal, "signal velocity");
      } else {
        double signal = p.sound_speed[i];
        terms_.for_each([&](const auto& t) {
          if constexpr (HasSignalSpeed<std::decay_t<decltype(t)>, D>)
            signal += t.signal_speed(i, in);
        });
        signal += p.velocity[i].norm();
        if (signal > 0) limit.consider(courant * h / signal, "Courant (eq 7)");
      }
      const double a = p.acceleration[i].norm();
      if (a > 0) limit.consider(courant * std::sqrt(h / a), "acceleration");
      // Cooling: an explicit step must not remove more than a fraction of u (without it,
      // an inviscid collision can drive u negative in one step; chapter 3).
      if constexpr (evolve_energy) {
        if (p.energy_rate[i] < 0 && p.internal_energy[i] > 0)
          limit.consider(courant * p.internal_energy[i] / -p.energy_rate[i], "cooling");
      }
      terms_.for_each([&](const auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (HasTimestep<T, D>) limit.consider(t.timestep(i, in), T::timestep_name);
      });
    }
    if constexpr (External::active) {
      limit.consider(external_.timestep(p.position[i], settings_.courant), External::timestep_name);
    }
    return limit;
  }

  // --- parts by type -------------------------------------------------------------------------
  template <class Part>
  void set(const Part& part) {
    if constexpr (std::is_same_v<Part, Settings>) {
      settings_ = part;
    } else if constexpr (std::is_same_v<Part, Eos>) {
      eos_ = part;
    } else if constexpr (std::is_same_v<Part, TermList>) {
      terms_ = part;
    } else if constexpr (TermList::template contains<Part>) {
      terms_.template get<Part>() = part;
    } else if constexpr (std::is_same_v<Part, Gravity>) {
      gravity_ = part;
    } else if constexpr (std::is_same_v<Part, External>) {
      external_ = part;
    } else if constexpr (std::is_same_v<Part, Boundaries>) {
      boundaries_ = part;
    } else if constexpr (std::is_same_v<Part, Integrator>) {
      integrator_ = part;
    } else {
      static_assert(
          std::is_same_v<Part, void>,
          "Simulation: this argument is not a part of the scene (its equation of state, one of its "
          "terms, Settings, its gravity, external potential, boundaries or integrator)");
    }
  }

  // --- the passes ----------------------------------------------------------------------------
  // Density, and in the same loop the equation of state and the terms' after_density hooks.
  void density_pass(ActiveSet active) {
    auto& p = particles_;
    // (the fields first: the hooks' view must point at their final arrays)
    fields_.resize(needs, p.size());
    const ParticleView<D> in = view();
    compute_density<D, K, needs>(
        p, search_.list(), in.x, settings_.density,
        [&](std::size_t i) {
          if constexpr (per_particle_eos) {
            p.pressure[i] = eos_.pressure(i, p.density[i]);
            p.sound_speed[i] = eos_.sound_speed(i, p.density[i]);
            p.internal_energy[i] = eos_.internal_energy(i, p.density[i]);
          } else {
            p.pressure[i] = eos_.pressure(p.density[i], p.internal_energy[i]);
            p.sound_speed[i] = eos_.sound_speed(p.density[i], p.internal_energy[i]);
          }
          fields_.p_over_rho2[i] = p.pressure[i] / (p.density[i] * p.density[i]);
          if constexpr (TermList::template any_after_density<D>) {
            terms_.for_each([&](auto& t) {
              if constexpr (HasAfterDensity<std::decay_t<decltype(t)>, D>) t.after_density(i, in);
            });
          }
        },
        in.v, &fields_, active);
  }

  // The gradient pass: a second loop over the same neighbour list, for the terms that have one.
  // Each such term sums its GradientSum over i's pairs, then finishes particle i.
  void gradient_pass(ActiveSet active) {
    const std::size_t n = particles_.size(), count = active.size(n);
    const ParticleView<D> in = view();
    const NeighbourList<D>& list = search_.list();
#pragma omp parallel for schedule(dynamic, 512) if (n >= parallel_threshold)
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = active[k];
      terms_.for_each([&](auto& t) {
        using T = std::decay_t<decltype(t)>;
        if constexpr (HasGradientPass<T, D>) {
          typename T::template GradientSum<D> sum{};
          for (const Neighbour& nb : list.of(i))
            t.gradient_pair(sum, pair_geometry<D, K>(in, i, nb), in);
          t.gradient_finish(i, sum, in);
        }
      });
    }
  }

  // The sums a term took in the force pass, finished particle by particle (before after_force,
  // which may use them).
  void finish_force_sums(ActiveSet active) {
    const ParticleView<D> in = view();
    per_particle(active, [&](auto& t, std::size_t i) {
      if constexpr (HasForceSum<std::decay_t<decltype(t)>, D>)
        t.force_sum_finish(i, force_sums_[i], in);
    });
  }

  // The terms' before_force hooks, particle by particle.
  void before_force(ActiveSet active) {
    const ParticleView<D> in = view();
    per_particle(active, [&](auto& t, std::size_t i) {
      if constexpr (HasBeforeForce<std::decay_t<decltype(t)>, D>) t.before_force(i, in);
    });
  }

  // Per-particle terms after the force pass: they add to a_i and du_i/dt.
  void after_force(ActiveSet active) {
    auto& p = particles_;
    const ParticleView<D> in = view();
    per_particle(active, [&](auto& t, std::size_t i) {
      if constexpr (HasAfterForce<std::decay_t<decltype(t)>, D>) {
        double dudt = evolve_energy ? p.energy_rate[i] : 0.0;
        t.after_force(i, in, p.acceleration[i], dudt);
        if constexpr (evolve_energy) p.energy_rate[i] = dudt;
      }
    });
  }

  // Call f(term, i) for every term and every particle (of `active`), in parallel over particles.
  template <class F>
  void per_particle(F&& f) {
    per_particle(ActiveSet{}, f);
  }
  template <class F>
  void per_particle(ActiveSet active, F&& f) {
    const std::size_t n = particles_.size(), count = active.size(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t k = 0; k < count; ++k) terms_.for_each([&](auto& t) { f(t, active[k]); });
  }

  void external_accelerations(ActiveSet active) {
    auto& p = particles_;
    const std::size_t n = p.size(), count = active.size(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = active[k];
      p.acceleration[i] += external_.acceleration(p.position[i]);
    }
  }

  // Two particles at one point see each other at r = 0, where the kernel gradient is zero:
  // nothing can ever push them apart, and the smoothing-length iteration of the density rule
  // chases h towards zero.  Stop at the start and name them.  (All particles at one point is
  // left to the neighbour search, whose message says exactly that.)
  void require_distinct_particles() const {
    const auto [lo, hi] = bounds<D>(particles_.position);
    if (particles_.size() < 2 || lo == hi) return;
    try {
      require_distinct_positions<D>(particles_.position);
    } catch (const Error& e) {
      throw Error(std::string(e.what()) +
                  ": SPH cannot separate two particles at one point (the kernel gradient "
                  "between them is zero); give every particle its own position");
    }
  }

  // A NaN or infinity must never travel on: stop and name the particle.
  void check_finite_forces() const {
    const auto& p = particles_;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!p.acceleration[i].allFinite() || !std::isfinite(p.energy_rate[i])) {
        throw Error("forces: particle " + show(i) + " at " + to_string<D>(p.position[i]) +
                    " has a non-finite acceleration or energy rate (rho = " + show(p.density[i]) +
                    ", P = " + show(p.pressure[i]) + ", h = " + show(p.smoothing_length[i]) + ")");
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
          throw Error(
              std::string("energy equation: ") + when + ", particle " + show(i) + " at " +
              to_string<D>(p.position[i]) + " has internal energy " + show(p.internal_energy[i]) +
              " at t = " + show(time_) +
              " (the step is too long for its cooling rate: lower the Courant factor, or use"
              " the exact update of a term that has one" +
              TermList::cooling_hints() + ")");
        }
      }
    }
  }

  Particles<D> particles_;
  Box<D> box_;
  Eos eos_{};
  TermList terms_{};
  Gravity gravity_{};
  External external_{};
  Boundaries boundaries_{};
  Integrator integrator_{};
  Settings settings_{};
  NeighbourSearch<D, K> search_;
  DerivedFields<D> fields_;
  std::vector<PairSum> force_sums_;  // a term's force-pass sums (terms.hpp), when one has them
  PositionArrays<D> positions_;      // the positions one array per axis, for the pair loops
  PositionArrays<D> velocities_;     // the velocities likewise
  static constexpr bool keeps_hydro_acceleration =
      hydro && TermList::template any_with_kick<D> && (Gravity::active || External::active);
  std::vector<Vec<D>> hydro_acceleration_;  // see hydro_acceleration()
  double time_ = 0;
  long steps_ = 0;
  std::size_t evaluated_ = 0;  // particles computed by the last evaluation
  TimestepLimit last_limit_;
  long constraint_failed_ = -1;  // the lowest particle a boundary could not bring back, if any
};

}  // namespace sph
