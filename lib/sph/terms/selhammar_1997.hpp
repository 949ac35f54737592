#pragma once
/// \file
/// \brief Selhammar's (1997) modified artificial viscosity: the restricted von
/// Neumann-Richtmyer term (eq 13) and the collective bulk term (eqs 14-19).
///
/// The standard viscosity (monaghan_gingold_1983.hpp) acts on every approaching pair.  In a
/// gas that is compressed smoothly, neighbours approach too -- at a speed that a few particles
/// per smoothing length cannot tell from a shock -- and the viscosity heats the gas and stops
/// the compression.  Selhammar keeps both terms of the standard viscosity but restricts where
/// they act.
///
/// **The restricted von Neumann-Richtmyer term** (eq 13) is the quadratic term alone,
/// \f$ \Pi_{ij} = \beta\mu_{ij}^2/\bar\rho_{ij} \f$, on only for a pair that approaches faster
/// than sound and faster than the compression of its neighbourhood explains.  In a flow that
/// compresses at the rate \f$ \dot\rho/\rho \f$, two particles a distance r apart approach at
/// \f$ (\dot\rho/D\rho)\, r \f$ (eqs 10-11, in D dimensions); only the excess over sound
/// speed beyond that is penetration.  With
/// \f$ s_{ij} = -\mathbf r_{ij}\cdot\mathbf v_{ij}/r_{ij} \f$
/// the approach speed (positive when approaching):
/// \f[ \text{on} \iff s_{ij} > \bar c_{ij} \quad\text{and}\quad
///     s_{ij} - \bar c_{ij} > \frac{\bar{\dot\rho}_{ij}}{D\bar\rho_{ij}}\, r_{ij}, \f]
/// with \f$ \dot\rho_i \f$ from the continuity equation (positive under compression).  The
/// paper prints the last inequality the other way round; RestrictedVonNeumannRichtmyer offers
/// that reading too, and chapter 5's homologous compression decides between them.
///
/// **The collective bulk term** (eqs 14-16) replaces the \f$ \alpha \f$ term.  Particle i
/// interacts once with the mean velocity of its neighbourhood, its own contribution removed,
/// \f[ \tilde{\mathbf v}_i = \frac{\sum_{j\ne i} \mathbf v_j V_{ij} w_{ij}}{N_i}, \qquad
///     V_{ij} = \bar m_{ij}/\bar\rho_{ij}, \f]
/// normalised so that \f$ \tilde{\mathbf v}_i = \mathbf v_i \f$ when every neighbour moves with
/// \f$ \mathbf v_i \f$: exactly with the neighbours' own sum of weights
/// \f$ N_i = \sum_{j\ne i} V_{ij} w_{ij} \f$ (Shepard, the default), or with the printed
/// \f$ N_i = 1 - w_i \f$, \f$ w_i = (m_i/\rho_i)\, w(0, h_i) \f$, which is the same where the
/// density is uniform (the density sum makes the weights add up to one there) and differs where
/// it is not.  Eq 16 is, with \f$ k_i = N_n\eta c_i/h_i \f$,
/// \f[ \dot{\mathbf v}_i = -k_i\,\hat{\mathbf v}_i
///     \sqrt{\lvert\mathbf v_i\cdot\Delta\mathbf v_i\rvert}
///     \quad\text{if } \mathbf v_i\cdot\Delta\mathbf v_i < 0, \f]
/// and what \f$ \Delta\mathbf v_i \f$ is, the print leaves open.  Eq 14 gives that name to the
/// mean velocity itself; read so (CollectiveReading::mean_velocity, the default), the term acts
/// on a particle that moves *against* the mean motion of its neighbourhood -- a particle of one
/// stream inside another, the penetration the term is meant to stop -- and nowhere in a flow
/// whose particles all move roughly together.  Read as the difference
/// \f$ \tilde{\mathbf v}_i - \mathbf v_i \f$ (CollectiveReading::difference), it acts on every
/// particle that outruns its neighbourhood, which in a real flow is half of them at any time:
/// a one-sided drag that removes momentum and kinetic energy everywhere.  The paper's weak shock
/// tube decides (chapter 5): with the difference reading the shock of its Fig 2 never forms.
/// In both readings the term changes only the speed \f$ w = \lvert\mathbf v_i\rvert \f$; with
/// \f$ a = \hat{\mathbf v}_i\cdot\tilde{\mathbf v}_i \f$ the neighbourhood's speed along
/// \f$ \hat{\mathbf v}_i \f$, \f$ \dot w = -k_i\sqrt{w\lvert a\rvert} \f$ while
/// \f$ a < 0 \f$ (mean velocity), or \f$ \dot w = -k_i\sqrt{w(w - a)} \f$ while
/// \f$ w > a \f$ (difference).  CollectiveMagnitude::projection replaces the root by
/// \f$ \lvert a\rvert \f$ or \f$ w - a \f$, linear in the velocities.
///
/// **It is stiff.**  The rate \f$ k_i = N_n\eta c_i/h_i \f$ is 64 times that of one pair of
/// the standard viscosity.  With the step of eq 7, \f$ \delta t = 0.3h/(w + c + 1.2\eta c) \f$,
/// an explicit kick of a particle meeting a head-on neighbourhood (\f$ \lvert a\rvert = w \f$)
/// changes its speed by \f$ k_i\delta t\, w = 19.2\eta\, w/(\mathcal M + 1 + 1.2\eta) \f$ with
/// \f$ \mathcal M = w/c \f$: more than w -- the particle is thrown backwards -- unless
/// \f$ \eta < (\mathcal M + 1)/18 \f$.  At \f$ \eta = 1 \f$ every head-on encounter slower
/// than Mach 17 overshoots, and each overshoot turns heat into kinetic energy.  The remedy used
/// by default: integrate the term's own equation exactly over the kick, with \f$ k_i \f$,
/// \f$ \hat{\mathbf v}_i \f$ and \f$ \tilde{\mathbf v}_i \f$ held.  For the mean-velocity
/// reading \f$ \sqrt w \f$ falls linearly,
/// \f$ w(\delta t) = \max(\sqrt{w_0} - \tfrac12 k_i\sqrt{|a|}\,\delta t,\ 0)^2 \f$; for the
/// difference reading \f$ \int dw/\sqrt{w(w - a)} = 2\ln(\sqrt w + \sqrt{w - a}) \f$ gives
/// \f[ S(\delta t) = \max\!\left(S_0\, e^{-k_i\delta t/2},\ \sqrt{|a|}\right), \quad
///     S_0 = \sqrt{w_0} + \sqrt{w_0 - a}, \quad
///     w(\delta t) = \frac{(S + a/S)^2}{4}. \f]
/// Either way w stops where the term switches off, whatever the step.
///
/// **Energy** (eqs 17-19).  The term is not a pair force, so its work is booked per
/// particle: after each kick the internal energy takes what the kinetic energy lost,
/// \f$ \Delta u_i = -\tfrac12(\lvert\mathbf v_\mathrm{after}\rvert^2 -
/// \lvert\mathbf v_\mathrm{without}\rvert^2) \f$, where \f$ \mathbf v_\mathrm{without} \f$ is
/// the velocity the kick would have given without this term.  For the explicit update this is
/// eq 19 corrected: \f$ \Delta u_i = -(\mathbf v\cdot\mathbf a_i\,\delta t +
/// \tfrac12 a_i^2\delta t^2) \f$ (the paper prints \f$ m_i/2 \f$ in the first term of eq 18 and
/// one \f$ \delta t \f$ too many in eq 19).  So \f$ \Delta T_i + \Delta U_i = 0 \f$ to
/// round-off, per particle and per kick.  Momentum is not conserved exactly: the neighbours do
/// not feel the reaction.
///
/// **Frame.**  As printed the term depends on \f$ \mathbf v_i \f$ itself, so what it does
/// depends on the frame of reference: in a frame where the whole gas moves fast, no particle
/// ever moves against its neighbourhood, and the mean-velocity reading never acts.
/// CollectiveFrame::neighbourhood evaluates eq 16 in the rest frame of the neighbourhood instead,
/// where \f$ \mathbf v_i \to \mathbf v_i - \tilde{\mathbf v}_i \f$ and the term becomes a
/// relaxation \f$ \dot{\mathbf v}_i = -k_i(\mathbf v_i - \tilde{\mathbf v}_i) \f$: Galilean
/// invariant, and acting on every deviation (it is the difference reading's limit).

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/fields.hpp"
#include "sph/kernel.hpp"
#include "sph/pair.hpp"
#include "sph/terms.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace sph {

/// Which way round the third condition of eq 13 is read.
enum class CompressionTest {
  /// on where \f$ s - \bar c > (\bar{\dot\rho}/D\bar\rho)\, r \f$ (our reading)
  excess_beyond_compression,
  as_printed,  ///< on where \f$ (\bar{\dot\rho}/D\bar\rho)\, r > s - \bar c \f$
  none,        ///< eq 12 alone: on for every supersonic approach
};

/// The restricted von Neumann-Richtmyer viscosity, Selhammar (1997) eq 13.  A bracket term
/// that asks the density pass for \f$ \dot\rho \f$.
struct RestrictedVonNeumannRichtmyer {
  static constexpr bool tracks_mu = true;  ///< the force pass keeps max_j mu_ij (eq 7)
  static constexpr Needs needs = Needs::density_rate;
  static constexpr const char* name = "Selhammar (1997) restricted vNR";

  double beta = 2.0;
  double nu2_factor = 0.01;  ///< nu^2 = nu2_factor * h_bar^2 (Selhammar: 1e-4)
  CompressionTest test = CompressionTest::excess_beyond_compression;

  RestrictedVonNeumannRichtmyer() = default;
  RestrictedVonNeumannRichtmyer(double b, double nu2 = 0.01,
                                CompressionTest t = CompressionTest::excess_beyond_compression)
      : beta(b), nu2_factor(nu2), test(t) {
    require(std::isfinite(b) && b >= 0,
            "restricted vNR viscosity: beta must be non-negative (got " + show(b) + ")");
    require(std::isfinite(nu2) && nu2 > 0,
            "restricted vNR viscosity: the nu^2 factor must be positive (got " + show(nu2) + ")");
  }

  std::string describe() const {
    const char* reading = test == CompressionTest::excess_beyond_compression ? "our reading"
                          : test == CompressionTest::as_printed              ? "as printed"
                                                                             : "eq 12 only";
    char s[128];
    std::snprintf(s, sizeof s, "restricted vNR, beta = %g, third condition %s", beta, reading);
    return s;
  }

  /// Whether the term acts on this pair (conditions of eq 13).  Branch-free, for the SIMD loop.
  template <int D>
  bool active(const Pair<D>& p, const ParticleView<D>& in) const {
    // With s = -rv/r the approach speed, the conditions multiplied through by r > 0 and by
    // D rho_bar > 0, so that the SIMD loop has no division: s > c_bar is -rv > c_bar r, and
    // s - c_bar > (rho_dot_bar / (D rho_bar)) r is D rho_bar (-rv - c_bar r) > rho_dot_bar r^2.
    const double c_bar = 0.5 * (in.c[p.i] + in.c[p.j]);
    const double rho_bar = 0.5 * (in.rho[p.i] + in.rho[p.j]);
    const double rate_bar = 0.5 * (in.density_rate[p.i] + in.density_rate[p.j]);
    const double excess = -p.rv - c_bar * p.r;          // (s - c_bar) r
    const double scaled_excess = D * rho_bar * excess;  // ... times D rho_bar
    const double explained = rate_bar * p.r2;  // (rho_dot_bar/(D rho_bar)) r times r D rho_bar
    const bool third = test == CompressionTest::excess_beyond_compression
                           ? scaled_excess > explained
                       : test == CompressionTest::as_printed ? explained > scaled_excess
                                                             : true;
    return (p.rv < 0) & (excess > 0) & third;
  }

  /// \f$ \Pi_{ij} = \beta\mu_{ij}^2/\bar\rho_{ij} \f$ where active, and \f$ |\mu_{ij}| \f$
  /// for the time step (only where active: a term that does not act sets no limit).
  template <int D>
  Bracket bracket(const Pair<D>& p, const ParticleView<D>& in) const {
    const double rho_bar = 0.5 * (in.rho[p.i] + in.rho[p.j]);
    const double mu =
        active(p, in) ? p.h_bar * p.rv / (p.r2 + nu2_factor * p.h_bar * p.h_bar) : 0.0;
    return {beta * mu * mu / rho_bar, p.r2 < p.support2 ? -mu : 0.0};
  }

  /// The quadratic part of eq 7's signal speed, \f$ 1.2\beta\mu_{i,\max} \f$.
  template <int D>
  double signal_speed(std::size_t i, const ParticleView<D>& in) const {
    return 1.2 * beta * in.max_mu[i];
  }
};

/// How the neighbourhood's velocity is normalised (eq 15).
enum class NeighbourhoodNormalisation {
  shepard,     ///< by the neighbours' own sum of weights: exact for a uniform velocity
  as_printed,  ///< by \f$ 1 - w_i \f$: exact only if all weights sum to one
};
/// How a kick applies the collective term.
enum class CollectiveUpdate {
  exact_relaxation,     ///< the term's own equation solved exactly over the kick (default)
  explicit_as_printed,  ///< an acceleration like any other, as in the paper (stiff)
};
/// What \f$ \Delta\mathbf v_i \f$ of eq 16 is.
enum class CollectiveReading {
  difference,  ///< \f$ \tilde{\mathbf v}_i - \mathbf v_i \f$: on when i outruns its neighbourhood
  mean_velocity,  ///< \f$ \tilde{\mathbf v}_i \f$ itself (eq 14's name): on when i moves against it
};
/// How the strength of eq 16 depends on the velocity difference.
enum class CollectiveMagnitude {
  root,        ///< \f$ \sqrt{|\mathbf v_i\cdot\Delta\mathbf v_i|} \f$, as printed
  projection,  ///< \f$ |\hat{\mathbf v}_i\cdot\Delta\mathbf v_i| \f$: linear in the difference
};
/// In which frame eq 16 is evaluated.
enum class CollectiveFrame {
  as_printed,     ///< with the particle's own velocity (depends on the frame of reference)
  neighbourhood,  ///< relative to the neighbourhood's velocity (Galilean invariant)
};

/// Selhammar's (1997) collective bulk viscosity, eqs 14-19, with its energy bookkeeping.  A term
/// with sums in the force pass (`force_sum_pair`, `force_sum_finish`: the neighbourhood's velocity
/// of eq 14, which only the kicks use, so it needs no loop of its own), an `after_force` hook (the
/// explicit acceleration), a `with_kick` hook (the exact update and the energy) and a signal speed
/// \f$ 1.2\eta c_i \f$ (eq 7, with \f$ \eta \f$ "used in the same way as \f$ \alpha \f$").
template <int D, class K = Kernel<D>>
struct SelhammarCollective {
  static constexpr const char* name = "Selhammar (1997) collective bulk viscosity";

  double eta = 1.0;
  double neighbours = 64;  ///< N_n, the mass of the virtual particle in units of m_i
  NeighbourhoodNormalisation normalisation = NeighbourhoodNormalisation::shepard;
  CollectiveUpdate update = CollectiveUpdate::exact_relaxation;
  CollectiveFrame frame = CollectiveFrame::as_printed;
  CollectiveMagnitude magnitude = CollectiveMagnitude::root;
  CollectiveReading reading = CollectiveReading::mean_velocity;

  // The term's own per-particle fields, from the last evaluation.
  std::vector<Vec<D>> neighbourhood_velocity;  ///< \f$ \tilde{\mathbf v}_i \f$
  std::vector<double> rate;                    ///< \f$ k_i = N_n\eta c_i/h_i \f$ (0: no neighbours)
  std::vector<Vec<D>> acceleration;            ///< the explicit update's acceleration (else zero)
  std::vector<unsigned char> fell_back;  ///< 1 where the printed normalisation fell back (w_i >= 1)

  SelhammarCollective() = default;
  SelhammarCollective(double eta_, double n_n,
                      NeighbourhoodNormalisation norm = NeighbourhoodNormalisation::shepard,
                      CollectiveUpdate upd = CollectiveUpdate::exact_relaxation,
                      CollectiveFrame fr = CollectiveFrame::as_printed)
      : eta(eta_), neighbours(n_n), normalisation(norm), update(upd), frame(fr) {
    require(std::isfinite(eta_) && eta_ >= 0,
            "collective viscosity: eta must be non-negative (got " + show(eta_) + ")");
    require(std::isfinite(n_n) && n_n >= 1,
            "collective viscosity: the neighbour number N_n must be at least 1 (got " + show(n_n) +
                ")");
  }
  std::string describe() const {
    char s[160];
    std::snprintf(
        s, sizeof s, "collective term, eta = %g, N_n = %g, %s, %s%s", eta, neighbours,
        normalisation == NeighbourhoodNormalisation::shepard ? "Shepard" : "1/(1-w_i)",
        update == CollectiveUpdate::exact_relaxation ? "exact relaxation" : "explicit kick",
        frame == CollectiveFrame::neighbourhood ? ", neighbourhood frame" : "");
    return s;
  }

  /// How many particles of the last evaluation fell back from the printed normalisation to
  /// Shepard's because \f$ w_i \ge 1 \f$ (a particle with very few neighbours).
  long fallbacks() const { return std::count(fell_back.begin(), fell_back.end(), 1); }

  void resize(std::size_t n) {
    neighbourhood_velocity.assign(n, Vec<D>::Zero());
    rate.assign(n, 0.0);
    fell_back.assign(n, 0);
    acceleration.assign(n, Vec<D>::Zero());
  }

  // --- the force-pass sums: eq 14 without i's own term -----------------------------------
  /// What the force pass sums for particle i (terms.hpp, PairSum): the weights of its
  /// neighbours, in `s[0]`, and their weighted velocities, in `s[1]` to `s[D]` (eq 14 without
  /// i's own term).  Only the kicks use the neighbourhood's velocity, so the sums are taken in
  /// the force loop itself, beside the forces, and need no loop over the neighbours of their own.
  PairSum force_sum_pair(const Pair<D>& p, const ParticleView<D>& in) const {
    const double volume = (in.m[p.i] + in.m[p.j]) / (in.rho[p.i] + in.rho[p.j]);  // m_bar/rho_bar
    const double w = volume * K::value(p.r, p.h_bar);
    PairSum sum;
    sum.s[0] = w;
    for (int a = 0; a < D; ++a) sum.s[1 + a] = w * in.v[a][p.j];
    return sum;
  }
  void force_sum_finish(std::size_t i, const PairSum& sum, const ParticleView<D>& in) {
    Vec<D> v_i;
    for (int a = 0; a < D; ++a) v_i[a] = in.v[a][i];
    if (!(sum.s[0] > 0)) {  // no neighbour but itself: no neighbourhood, no collective term
      neighbourhood_velocity[i] = v_i;
      rate[i] = 0;
      return;
    }
    double norm = sum.s[0];
    if (normalisation == NeighbourhoodNormalisation::as_printed) {
      const double self = in.m[i] / in.rho[i] * K::value(0.0, in.h[i]);
      fell_back[i] = !(self < 1);
      if (self < 1) norm = 1 - self;
    }
    for (int a = 0; a < D; ++a) neighbourhood_velocity[i][a] = sum.s[1 + a] / norm;
    rate[i] = neighbours * eta * in.c[i] / in.h[i];
  }

  /// The explicit update: eq 16 as an acceleration at the velocities of the evaluation.
  void after_force(std::size_t i, const ParticleView<D>& in, Vec<D>& a, double&) {
    if (update != CollectiveUpdate::explicit_as_printed) return;
    Vec<D> v;
    for (int k = 0; k < D; ++k) v[k] = in.v[k][i];
    acceleration[i] = explicit_acceleration(i, v);
    a += acceleration[i];
  }

  /// Eq 16 at velocity v, with this evaluation's neighbourhood and rate.
  Vec<D> explicit_acceleration(std::size_t i, const Vec<D>& v) const {
    const Vec<D>& mean = neighbourhood_velocity[i];
    if (frame == CollectiveFrame::neighbourhood) return -rate[i] * (v - mean);
    const double w = v.norm();
    if (!(w > 0)) return Vec<D>::Zero();
    const Vec<D> unit = v / w;
    const double along = unit.dot(mean);  // a: the neighbourhood's speed along v_i
    const double k = rate[i];
    if (reading == CollectiveReading::difference) {
      if (!(w > along)) return Vec<D>::Zero();
      if (magnitude == CollectiveMagnitude::projection) return -k * (w - along) * unit;
      return -k * std::sqrt(w * (w - along)) * unit;
    }
    if (!(along < 0)) return Vec<D>::Zero();
    if (magnitude == CollectiveMagnitude::projection) return k * along * unit;
    return -k * std::sqrt(-w * along) * unit;
  }

  /// The exact update of v over dt by the term alone (k, v-hat and the neighbourhood held).
  Vec<D> relaxed(std::size_t i, const Vec<D>& v, double dt) const {
    const Vec<D>& mean = neighbourhood_velocity[i];
    const double k = rate[i];
    if (frame == CollectiveFrame::neighbourhood) return mean + std::exp(-k * dt) * (v - mean);
    const double w = v.norm();
    if (!(w > 0)) return v;
    const Vec<D> unit = v / w;
    const double along = unit.dot(mean);
    if (reading == CollectiveReading::mean_velocity) {
      if (!(along < 0)) return v;
      if (magnitude == CollectiveMagnitude::projection) {  // dw/dt = k a: linear, stops at 0
        return std::max(w + k * along * dt, 0.0) * unit;
      }
      // dw/dt = -k sqrt(w |a|): sqrt(w) falls linearly, stops at 0
      const double root = std::max(std::sqrt(w) - 0.5 * k * std::sqrt(-along) * dt, 0.0);
      return (root * root) * unit;
    }
    if (!(w > along)) return v;
    if (magnitude == CollectiveMagnitude::projection) {  // w - a decays as exp(-k t), w stops at 0
      return std::max(along + (w - along) * std::exp(-k * dt), 0.0) * unit;
    }
    const double s0 = std::sqrt(w) + std::sqrt(w - along);
    const double s = std::max(s0 * std::exp(-0.5 * k * dt), std::sqrt(std::abs(along)));
    const double root = s + along / s;
    return (0.25 * root * root) * unit;
  }

  /// After a kick by dt: the exact update (default), and the energy the term took from the
  /// kinetic energy given to u (eqs 17-19, corrected).
  void with_kick(std::size_t i, double dt, const Vec<D>&, Vec<D>& v, double& u) const {
    if (update == CollectiveUpdate::explicit_as_printed) {
      const Vec<D> without = v - dt * acceleration[i];
      u -= 0.5 * (v.squaredNorm() - without.squaredNorm());
    } else {
      const Vec<D> after = relaxed(i, v, dt);
      u -= 0.5 * (after.squaredNorm() - v.squaredNorm());
      v = after;
    }
  }

  /// The collective part of eq 7's signal speed, \f$ 1.2\eta c_i \f$.
  double signal_speed(std::size_t i, const ParticleView<D>& in) const {
    return 1.2 * eta * in.c[i];
  }
};

/// Where the restricted vNR term acts: of the pairs inside the kernel that approach faster than
/// sound, how many it is on for.  The test of eq 13's third condition (chapter 5): in a
/// homologous compression the fraction must stay near zero.
struct VnrCensus {
  long supersonic = 0;  ///< approaching pairs with \f$ s_{ij} > \bar c_{ij} \f$, r < 2 h_bar
  long on = 0;          ///< of those, the pairs the term acts on
  double fraction() const { return supersonic > 0 ? double(on) / double(supersonic) : 0.0; }
};

/// The census of the term RestrictedVonNeumannRichtmyer of a simulation, at its last evaluation,
/// over the pairs whose particle i satisfies `include(i)` (all by default).
struct EveryParticle {
  bool operator()(std::size_t) const { return true; }
};
template <class Sim, class Include = EveryParticle>
VnrCensus vnr_census(const Sim& sim, const Include& include = {}) {
  constexpr int D = Sim::D;
  const auto in = sim.view();
  const auto& list = sim.neighbours();
  const auto& term = sim.template term<RestrictedVonNeumannRichtmyer>();
  VnrCensus census;
  for (std::size_t i = 0; i < sim.particles().size(); ++i) {
    if (!include(i)) continue;
    for (const auto& nb : list.of(i)) {
      const Pair<D> pair = pair_geometry<D, typename Sim::K>(in, i, nb);
      if (!(pair.rv < 0) || !(pair.r2 < pair.support2)) continue;
      if (-pair.rv / pair.r <= 0.5 * (in.c[pair.i] + in.c[pair.j])) continue;
      ++census.supersonic;
      if (term.active(pair, in)) ++census.on;
    }
  }
  return census;
}

}  // namespace sph
