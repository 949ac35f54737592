#pragma once
/// \file
/// \brief A term of the equations of motion, and the list of terms a scene names.
///
/// A **term** is one file and one type: the pressure force, an artificial viscosity, a
/// physical viscosity, a per-particle drag.  It brings any of the following, and the step
/// calls exactly what it brings -- a member a term does not have is never called, and a term
/// a scene does not name is never compiled into its step (after SWIFT's split into per-particle
/// hooks, `hydro.h`, and pure pair functions, `hydro_iact.h`).  This table is the one list of
/// the slots; a member named like a slot whose signature does not fit it is a compile error
/// (check_slots), and the page \ref writing_a_term walks through a real term.
///
/// \anchor term_slots
/// | member | slot | what it does |
/// |:--|:--|:--|
/// | `needs` | density pass | fields summed beside rho: Needs::density_rate, velocity_divergence, velocity_curl |
/// | `resize(n)` | set-up | allocates the term's own per-particle fields (members of the term) |
/// | `after_density(i, view)` | density pass | per particle, right after rho_i, P_i, c_i |
/// | `GradientSum<D>`, `gradient_pair(sum, pair, view)`, `gradient_finish(i, sum, view)` | gradient pass | a second loop over the same neighbour list |
/// | `force_sum_pair(pair, view)`, `force_sum_finish(i, sum, view)` | force pass | up to four sums over the pairs, taken in the force loop itself, for what only the kicks use |
/// | `before_force(i, view)` | before the force pass | per particle |
/// | `bracket(pair, view)` | force pass | adds to the symmetric bracket \f$ P_i/\rho_i^2 + P_j/\rho_j^2 + \Pi_{ij} \f$ |
/// | `heating(pair, view)` | force pass | with a bracket: the factor \f$ H_{ij} \f$ of its heating, in place of \f$ \tfrac12 B_{ij} \f$ |
/// | `pair_acceleration(pair, view)` | force pass | a non-central pair acceleration and its heating |
/// | `after_force(i, view, a_i, dudt_i)` | after the force pass | per-particle accelerations (Selhammar's collective term) |
/// | `with_kick(i, dt, v_before, v, u)` | integrator | after each kick of particle i by dt, from velocity v_before to v: may change v (a term integrated exactly over the kick) and u (energy bookkeeping, or a per-particle coefficient's own equation); u is a dummy when the gas does not evolve it |
/// | `signal_speed(i, view)` | time step | adds to the signal speed of the Courant criterion (eq 7) |
/// | `timestep(i, view)`, `timestep_name` | time step | a limit of its own, reported by name when it limits |
/// | `cooling_hint` | energy check | a sentence added to the message when a particle's internal energy goes negative |
///
/// **The bracket.**  The momentum and energy equations of Selhammar (1997) eq 4 share one
/// symmetric factor per pair: \f$ \mathbf a_i \mathrel{-}= m_j B_{ij} \nabla_i W_{ij} \f$ and
/// \f$ \dot u_i \mathrel{+}= \tfrac12 m_j B_{ij}\,\mathbf v_{ij}\cdot\nabla_i W_{ij} \f$.  A term
/// that only adds to \f$ B_{ij} \f$ is central, conserves momentum and energy by construction,
/// and keeps the force loop a SIMD loop: a scene whose terms are all of this kind compiles to
/// the same vectorised loop as a scene with the pressure force alone.  A term whose force is
/// not along \f$ \mathbf r_{ij} \f$ (Watkins' Navier-Stokes viscosity) returns a
/// PairAcceleration instead; momentum is then conserved only if the term makes it
/// antisymmetric itself, which Watkins' differenced sums are not (chapter 7 measures the net
/// force they leave).
///
/// **Who is heated.**  By default the work of a bracket term is shared equally by the pair, the
/// \f$ \tfrac12 B_{ij} \f$ above.  A term may say otherwise with `heating(pair, view)`, the
/// factor \f$ H_{ij} \f$ in
/// \f$ \dot u_i \mathrel{+}= m_j H_{ij}\,\mathbf v_{ij}\cdot\nabla_i W_{ij} \f$:
/// energy is still conserved when \f$ H_{ij} + H_{ji} = B_{ij} \f$ (the pressure term whose
/// particles each do the work of their own pressure, \f$ H_{ij} = P_i/\rho_i^2 \f$, is one).

#include "sph/dimension.hpp"
#include "sph/fields.hpp"
#include "sph/pair.hpp"
#include "sph/particles.hpp"

#include <concepts>
#include <cstddef>
#include <tuple>
#include <string>
#include <type_traits>

namespace sph {

/// What a bracket term adds to \f$ B_{ij} \f$ for one pair, and the \f$ |\mu_{ij}| \f$ it saw
/// (for the time step of eq 7; zero for terms that do not track it).
struct Bracket {
  double value = 0;
  double mu = 0;
  double heat = 0;  ///< the heating factor H_ij (summed only when some term has `heating`)
};

/// What one pair adds to a term's sums in the force pass (PairSum: up to four numbers, plain
/// scalars so that the SIMD lanes keep them in registers).  A term whose per-particle sum is
/// needed only after the forces -- Selhammar's neighbourhood velocity, which only the kicks use
/// -- takes it here instead of in a gradient pass of its own, and saves that pass's loop over
/// the neighbours.  One term of a scene at most may have such sums.
struct PairSum {
  double s[4] = {0, 0, 0, 0};
};

/// A non-central acceleration of particle i by one pair, and the heating of i that goes with
/// it.  Plain scalars (the first D of `a` are used), so SIMD lanes keep them in registers.
struct PairAcceleration {
  double a[3] = {0, 0, 0};
  double heat = 0;
};

// --- what a term has (each member is optional) ---------------------------------------------
template <class T>
concept HasNeeds = requires {
  { T::needs } -> std::convertible_to<Needs>;
};
template <class T>
concept HasResize = requires(T t, std::size_t n) {
  t.resize(n);
};
template <class T, int D>
concept HasBracket = requires(const T t, const Pair<D>& pair, const ParticleView<D>& view) {
  { t.bracket(pair, view) } -> std::same_as<Bracket>;
};
template <class T, int D>
concept HasHeating = requires(const T t, const Pair<D>& pair, const ParticleView<D>& view) {
  { t.heating(pair, view) } -> std::convertible_to<double>;
};
template <class T, int D>
concept HasPairAcceleration = requires(const T t, const Pair<D>& pair,
                                       const ParticleView<D>& view) {
  { t.pair_acceleration(pair, view) } -> std::same_as<PairAcceleration>;
};
template <class T, int D>
concept HasGradientPass = requires(T t, typename T::template GradientSum<D>& sum,
                                   const Pair<D>& pair, const ParticleView<D>& view,
                                   std::size_t i) {
  t.gradient_pair(sum, pair, view);
  t.gradient_finish(i, sum, view);
};
template <class T, int D>
concept HasForceSum = requires(const T t, T tm, const Pair<D>& pair, const ParticleView<D>& view,
                               std::size_t i, const PairSum& sum) {
  { t.force_sum_pair(pair, view) } -> std::same_as<PairSum>;
  tm.force_sum_finish(i, sum, view);
};
template <class T>
concept HasCoolingHint = requires {
  { T::cooling_hint } -> std::convertible_to<const char*>;
};
template <class T, int D>
concept HasAfterDensity = requires(T t, std::size_t i, const ParticleView<D>& view) {
  t.after_density(i, view);
};
template <class T, int D>
concept HasBeforeForce = requires(T t, std::size_t i, const ParticleView<D>& view) {
  t.before_force(i, view);
};
// The hooks that change a particle's a, du/dt, v or u take them by (non-const) reference: a
// member that takes them by value would compile, be called, and change only its copies, so a
// call with temporaries in their places must not compile.
template <class T, int D>
concept HasAfterForce = requires(T t, std::size_t i, const ParticleView<D>& view, Vec<D>& a,
                                 double& dudt) {
  t.after_force(i, view, a, dudt);
}
&&!requires(T t, std::size_t i, const ParticleView<D>& view, double& dudt) {
  t.after_force(i, view, Vec<D>{}, dudt);
}
&&!requires(T t, std::size_t i, const ParticleView<D>& view, Vec<D>& a) {
  t.after_force(i, view, a, 0.0);
};
template <class T, int D>
concept HasWithKick = requires(T t, std::size_t i, double dt, const Vec<D>& v_before, Vec<D>& v,
                               double& u) {
  t.with_kick(i, dt, v_before, v, u);
}
&&!requires(T t, std::size_t i, double dt, const Vec<D>& v_before, double& u) {
  t.with_kick(i, dt, v_before, Vec<D>{}, u);
}
&&!requires(T t, std::size_t i, double dt, const Vec<D>& v_before, Vec<D>& v) {
  t.with_kick(i, dt, v_before, v, 0.0);
};
template <class T, int D>
concept HasSignalSpeed = requires(const T t, std::size_t i, const ParticleView<D>& view) {
  { t.signal_speed(i, view) } -> std::convertible_to<double>;
};
template <class T, int D>
concept HasTimestep = requires(const T t, std::size_t i, const ParticleView<D>& view) {
  { t.timestep(i, view) } -> std::convertible_to<double>;
  { T::timestep_name } -> std::convertible_to<const char*>;
};

/// Whether the step recognises at least one member of term T: a term whose members all have
/// the wrong signature would otherwise be silently left out of the step.
template <class T, int D>
concept RecognisedTerm = HasNeeds<T> || HasResize<T> || HasBracket<T, D> ||
    HasPairAcceleration<T, D> || HasHeating<T, D> || HasGradientPass<T, D> || HasForceSum<T, D> ||
    HasAfterDensity<T, D> || HasBeforeForce<T, D> || HasAfterForce<T, D> || HasWithKick<T, D> ||
    HasSignalSpeed<T, D> || HasTimestep<T, D>;

// --- a member named like a slot must fit the slot ------------------------------------------
// The concepts above ask "does T have this member with this signature?"; a member with the right
// name and a wrong signature answers "no", and the step would silently never call it.  So we
// also ask "does T have a member of this name at all?", whatever its kind or signature, and
// refuse a term where the two answers differ.  C++20 has no reflection to ask it directly; the
// classic way is an ambiguity: a class derived from T and from a probe that has a member of the
// name finds that name twice exactly when T has it too, and then `&Probe<T>::name` does not
// compile.

namespace slot_names {
#define SPH_SLOT_NAME(slot)                 \
  struct slot##_probe {                     \
    int slot;                               \
  };                                        \
  template <class T>                        \
  struct slot##_mixin : T, slot##_probe {}; \
  template <class T>                        \
  concept has_##slot = !requires {          \
    &slot##_mixin<T>::slot;                 \
  };
SPH_SLOT_NAME(needs)
SPH_SLOT_NAME(resize)
SPH_SLOT_NAME(after_density)
SPH_SLOT_NAME(GradientSum)
SPH_SLOT_NAME(gradient_pair)
SPH_SLOT_NAME(gradient_finish)
SPH_SLOT_NAME(force_sum_pair)
SPH_SLOT_NAME(force_sum_finish)
SPH_SLOT_NAME(before_force)
SPH_SLOT_NAME(bracket)
SPH_SLOT_NAME(heating)
SPH_SLOT_NAME(pair_acceleration)
SPH_SLOT_NAME(after_force)
SPH_SLOT_NAME(with_kick)
SPH_SLOT_NAME(signal_speed)
SPH_SLOT_NAME(timestep)
SPH_SLOT_NAME(timestep_name)
SPH_SLOT_NAME(cooling_hint)
#undef SPH_SLOT_NAME
}  // namespace slot_names

/// Every member of term T that is named like a slot fits that slot in D dimensions; a member
/// that does not is a compile error naming the slot and the signature it expects (the table
/// above).  Checked for every term of a Simulation.
template <class T, int D>
constexpr bool check_slots() {
  namespace n = slot_names;
  static_assert(!n::has_needs<T> || HasNeeds<T>,
                "term slot `needs` expects: static constexpr sph::Needs needs = ...;");
  static_assert(!n::has_resize<T> || HasResize<T>,
                "term slot `resize` expects: void resize(std::size_t n)");
  static_assert(!n::has_after_density<T> || HasAfterDensity<T, D>,
                "term slot `after_density` expects: "
                "void after_density(std::size_t i, const sph::ParticleView<D>& view)");
  static_assert(!(n::has_GradientSum<T> || n::has_gradient_pair<T> || n::has_gradient_finish<T>) ||
                    HasGradientPass<T, D>,
                "term slot `gradient pass` expects all three: template <int D> struct "
                "GradientSum; void gradient_pair(GradientSum<D>& sum, const sph::Pair<D>& pair, "
                "const sph::ParticleView<D>& view) const; "
                "void gradient_finish(std::size_t i, GradientSum<D>& sum, "
                "const sph::ParticleView<D>& view)");
  static_assert(!(n::has_force_sum_pair<T> || n::has_force_sum_finish<T>) || HasForceSum<T, D>,
                "term slot `force sums` expects both: sph::PairSum force_sum_pair(const "
                "sph::Pair<D>& pair, const sph::ParticleView<D>& view) const; "
                "void force_sum_finish(std::size_t i, const sph::PairSum& sum, "
                "const sph::ParticleView<D>& view)");
  static_assert(!n::has_before_force<T> || HasBeforeForce<T, D>,
                "term slot `before_force` expects: "
                "void before_force(std::size_t i, const sph::ParticleView<D>& view)");
  static_assert(!n::has_bracket<T> || HasBracket<T, D>,
                "term slot `bracket` expects: sph::Bracket bracket(const sph::Pair<D>& pair, "
                "const sph::ParticleView<D>& view) const");
  static_assert(!n::has_heating<T> || HasHeating<T, D>,
                "term slot `heating` expects: double heating(const sph::Pair<D>& pair, "
                "const sph::ParticleView<D>& view) const");
  static_assert(!n::has_pair_acceleration<T> || HasPairAcceleration<T, D>,
                "term slot `pair_acceleration` expects: sph::PairAcceleration "
                "pair_acceleration(const sph::Pair<D>& pair, const sph::ParticleView<D>& view) "
                "const");
  static_assert(!n::has_after_force<T> || HasAfterForce<T, D>,
                "term slot `after_force` expects: void after_force(std::size_t i, "
                "const sph::ParticleView<D>& view, sph::Vec<D>& a, double& dudt)");
  static_assert(!n::has_with_kick<T> || HasWithKick<T, D>,
                "term slot `with_kick` expects: void with_kick(std::size_t i, double dt, "
                "const sph::Vec<D>& v_before, sph::Vec<D>& v, double& u)");
  static_assert(!n::has_signal_speed<T> || HasSignalSpeed<T, D>,
                "term slot `signal_speed` expects: double signal_speed(std::size_t i, "
                "const sph::ParticleView<D>& view) const");
  static_assert(!(n::has_timestep<T> || n::has_timestep_name<T>) || HasTimestep<T, D>,
                "term slot `timestep` expects both: double timestep(std::size_t i, "
                "const sph::ParticleView<D>& view) const; "
                "static constexpr const char* timestep_name = \"...\";");
  static_assert(!n::has_cooling_hint<T> || HasCoolingHint<T>,
                "term slot `cooling_hint` expects: static constexpr const char* cooling_hint = "
                "\"...\";");
  return true;
}

/// The fields term T asks the density pass for.
template <class T>
constexpr Needs needs_of() {
  if constexpr (HasNeeds<T>) {
    return T::needs;
  } else {
    return Needs::nothing;
  }
}

/// The terms of a scene, in the order they add up (the pressure term first: sums are taken in
/// this order, so the order is part of the result's last bits).  Each term is a value with its
/// parameters (and its own fields), held in a tuple.
///
///     using Terms = sph::Terms<sph::PressureHernquistKatz, sph::MonaghanGingold1983>;
template <class... T>
struct Terms {
  std::tuple<T...> parts;

  Terms() = default;
  /// The terms with their parameters, in the order of the list: `{{}, MonaghanGingold1983{1, 2}}`.
  Terms(const T&... terms) requires(sizeof...(T) > 0) : parts(terms...) {}

  static constexpr std::size_t count = sizeof...(T);
  /// Every field the density pass must sum for these terms.
  static constexpr Needs needs = (Needs::nothing | ... | needs_of<T>());
  /// Whether U is one of the terms.
  template <class U>
  static constexpr bool contains = (std::is_same_v<U, T> || ...);
  /// Whether the step recognises every term, in D dimensions (see RecognisedTerm).
  template <int D>
  static constexpr bool all_recognised = (RecognisedTerm<T, D> && ...);
  /// Every member of every term named like a slot fits it (a compile error otherwise).
  template <int D>
  static constexpr bool slots_fit = (check_slots<T, D>() && ...);
  /// Whether any term has a member of the given kind, in D dimensions.
  template <int D>
  static constexpr bool any_bracket = (HasBracket<T, D> || ...);
  template <int D>
  static constexpr bool any_heating = (HasHeating<T, D> || ...);
  template <int D>
  static constexpr bool any_pair_acceleration = (HasPairAcceleration<T, D> || ...);
  template <int D>
  static constexpr bool any_gradient_pass = (HasGradientPass<T, D> || ...);
  /// How many terms take sums in the force pass (at most one may).
  template <int D>
  static constexpr int force_sum_terms = (int(HasForceSum<T, D>) + ... + 0);
  template <int D>
  static constexpr bool any_force_sum = force_sum_terms<D> > 0;
  template <int D>
  static constexpr bool any_after_density = (HasAfterDensity<T, D> || ...);
  template <int D>
  static constexpr bool any_before_force = (HasBeforeForce<T, D> || ...);
  template <int D>
  static constexpr bool any_after_force = (HasAfterForce<T, D> || ...);
  template <int D>
  static constexpr bool any_with_kick = (HasWithKick<T, D> || ...);
  /// The terms' hints for the message of a negative internal energy (`cooling_hint`), joined.
  static std::string cooling_hints() {
    std::string text;
    (
        [&] {
          if constexpr (HasCoolingHint<T>) text += std::string("; ") + T::cooling_hint;
        }(),
        ...);
    return text;
  }
  /// Whether any term reports \f$ \mu_{ij} \f$ (then the force pass keeps its maximum).
  static constexpr bool tracks_mu = (requires { T::tracks_mu; } || ...);

  /// Term U.
  template <class U>
  U& get() {
    return std::get<U>(parts);
  }
  template <class U>
  const U& get() const {
    return std::get<U>(parts);
  }

  /// Call f(term) for every term, in order.
  template <class F>
  void for_each(F&& f) {
    std::apply([&](auto&... t) { (f(t), ...); }, parts);
  }
  template <class F>
  void for_each(F&& f) const {
    std::apply([&](const auto&... t) { (f(t), ...); }, parts);
  }
};

/// The sum of the bracket terms for one pair (in the order of the list), the largest
/// \f$ \mu_{ij} \f$ they report, and -- when some term says who is heated -- the heating factor
/// \f$ \sum H_{ij} \f$ (\f$ \tfrac12 B_{ij} \f$ for the terms that do not say).
template <int D, class... T>
inline Bracket bracket_of(const Terms<T...>& terms, const Pair<D>& pair,
                          const ParticleView<D>& view) {
  constexpr bool heating = Terms<T...>::template any_heating<D>;
  Bracket sum;
  terms.for_each([&](const auto& t) {
    using Term = std::decay_t<decltype(t)>;
    if constexpr (HasBracket<Term, D>) {
      const Bracket b = t.bracket(pair, view);
      sum.value += b.value;
      sum.mu = std::max(sum.mu, b.mu);
      if constexpr (heating) {
        if constexpr (HasHeating<Term, D>) {
          sum.heat += t.heating(pair, view);
        } else {
          sum.heat += 0.5 * b.value;
        }
      }
    }
  });
  return sum;
}

/// The sum of the non-central pair accelerations for one pair.
template <int D, class... T>
inline PairAcceleration pair_acceleration_of(const Terms<T...>& terms, const Pair<D>& pair,
                                             const ParticleView<D>& view) {
  PairAcceleration sum;
  terms.for_each([&](const auto& t) {
    if constexpr (HasPairAcceleration<std::decay_t<decltype(t)>, D>) {
      const PairAcceleration a = t.pair_acceleration(pair, view);
      for (int k = 0; k < D; ++k) sum.a[k] += a.a[k];
      sum.heat += a.heat;
    }
  });
  return sum;
}

/// The force-pass sums of one pair: those of the one term that has them.
template <int D, class... T>
inline PairSum force_sum_of(const Terms<T...>& terms, const Pair<D>& pair,
                            const ParticleView<D>& view) {
  static_assert(Terms<T...>::template force_sum_terms<D> <= 1,
                "at most one term of a scene may take sums in the force pass");
  PairSum sum;
  terms.for_each([&](const auto& t) {
    if constexpr (HasForceSum<std::decay_t<decltype(t)>, D>) sum = t.force_sum_pair(pair, view);
  });
  return sum;
}

}  // namespace sph
