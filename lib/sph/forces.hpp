#pragma once
/// \file
/// \brief The force pass: one loop over the neighbour list that adds up the scene's terms.
///
/// Selhammar (1997) eq 4, in the Hernquist & Katz (1989) form with the sign of his eq 6:
/// \f[ \frac{d\mathbf v_i}{dt} = -\sum_j m_j \left( \frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}
///       + \Pi_{ij} \right) \nabla_i W(r_{ij}, \bar h_{ij}), \qquad
///     \frac{du_i}{dt} = \frac12 \sum_j m_j \left( \frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}
///       + \Pi_{ij} \right) \mathbf v_{ij}\cdot\nabla_i W(r_{ij}, \bar h_{ij}). \f]
/// The bracket is symmetric in i and j and the kernel gradient antisymmetric, so every pair
/// exerts equal and opposite forces: momentum is conserved to round-off, and the energy the
/// pair removes from the motion it puts into heat, shared equally.  Which terms make up the
/// bracket is the scene's choice (terms.hpp): the pressure term, a viscosity, ...; terms whose
/// force is not along the line of centres add a PairAcceleration of their own.
///
/// The pass is a gather loop: particle i sums over its neighbour list and writes only its own
/// acceleration and energy rate.  Each pair is therefore evaluated twice, once from each side,
/// but the threads need no locks and the result is bitwise the same for any thread count.
///
/// Everything here is chosen at compile time.  pair_force has no branches (a pair outside the
/// kernel at h_bar, or receding, contributes exact zeros), so the compiler runs the loop over
/// one particle's neighbours on eight pairs at once in SIMD registers; what a scene does not
/// name -- a viscosity, a non-central term, the energy equation of a polytropic gas -- is not
/// in its loop at all.

#include "sph/error.hpp"
#include "sph/fields.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/pair.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"
#include "sph/terms.hpp"

#include <algorithm>
#include <span>
#include <type_traits>
#include <vector>

namespace sph {

/// What one pair adds to particle i: the bracket factor \f$ f = m_j B_{ij} g \f$ (acceleration
/// \f$ -f\,\mathbf r_{ij} \f$, heating \f$ \tfrac12 f\, \mathbf r_{ij}\cdot\mathbf v_{ij} \f$), the
/// non-central terms' acceleration and heating, and \f$ |\mu_{ij}| \f$.  (Plain scalars, so the
/// compiler keeps them in registers across the SIMD lanes.)
struct NoPairAcceleration {};
struct NoHeatingFactor {};
struct NoSignalVelocity {};
struct NoPairSum {};
/// What one pair contributes in the force pass: the central factor, the non-central
/// acceleration and heating (present only if a term has them), \f$ |\mu_{ij}| \f$ and, with the
/// signal-velocity time step, the pair's signal speed.
template <bool with_extra, bool with_heating, bool with_signal = false, bool with_sum = false>
struct PairForce {
  double f, rv, mu;
  double r_ij[3];  // the first D are used
  /// The non-central part: an empty member (no storage) when no term of the scene has one.
  [[no_unique_address]] std::conditional_t<with_extra, PairAcceleration, NoPairAcceleration> extra;
  /// \f$ m_j H_{ij} g \f$ when a term says who is heated
  /// (else \f$ \tfrac12 f \f$ is used; no storage).
  [[no_unique_address]] std::conditional_t<with_heating, double, NoHeatingFactor> f_heat;
  /// \f$ v_{\rm sig,ij} \f$ of Monaghan (1997) when the time step asks for it (else no storage).
  [[no_unique_address]] std::conditional_t<with_signal, double, NoSignalVelocity> signal;
  /// A term's force-pass sums (PairSum) when a term of the scene takes them (else no storage).
  [[no_unique_address]] std::conditional_t<with_sum, PairSum, NoPairSum> sum;
};

/// The force between particle i and one neighbour: the geometry, then every term of the scene.
/// With \p with_signal, also the pair's signal velocity of Monaghan (1997),
/// \f$ v_{\rm sig,ij} = c_i + c_j - \beta_{\rm sig}\, w_{ij} \f$ with
/// \f$ w_{ij} = \mathbf v_{ij}\cdot\hat{\mathbf r}_{ij} \f$ for an approaching pair and 0 for a
/// receding one (zero outside the kernel's support at \f$ \bar h_{ij} \f$).
template <int D, class K, class TermList, bool with_signal = false>
inline auto pair_force(const ParticleView<D>& in, const TermList& terms, std::size_t i,
                       const Neighbour& nb, double signal_beta = 0.0) {
  const Pair<D> pr = pair_geometry<D, K>(in, i, nb);
  constexpr bool heating = TermList::template any_heating<D>;
  constexpr bool with_sum = TermList::template any_force_sum<D>;
  PairForce<TermList::template any_pair_acceleration<D>, heating, with_signal, with_sum> out;
  const Bracket bracket = bracket_of<D>(terms, pr, in);
  // Equal and opposite: the factor m_j * bracket * g multiplies the antisymmetric r_ij.
  out.f = in.m[pr.j] * bracket.value * pr.gradient_factor;
  if constexpr (heating) out.f_heat = in.m[pr.j] * bracket.heat * pr.gradient_factor;
  out.rv = pr.rv;
  out.mu = bracket.mu;
#pragma GCC unroll 3
  for (int a = 0; a < D; ++a) out.r_ij[a] = pr.r_ij[a];
  if constexpr (TermList::template any_pair_acceleration<D>)
    out.extra = pair_acceleration_of<D>(terms, pr, in);
  if constexpr (with_sum) out.sum = force_sum_of<D>(terms, pr, in);
  if constexpr (with_signal) {
    // (rv < 0 implies r > 0; the branches are selects, the loop stays vectorised)
    const double w = pr.rv < 0 ? pr.rv / pr.r : 0.0;
    out.signal = pr.r2 < pr.support2 ? in.c[i] + in.c[pr.j] - signal_beta * w : 0.0;
  }
  return out;
}

/// The force pass.  Writes p.acceleration, p.energy_rate (when the gas evolves its energy),
/// when a term tracks it fields.max_mu, and with \p track_signal fields.max_signal, the largest
/// signal velocity of Monaghan (1997) over each particle's pairs (with \p signal_beta as its
/// \f$ \beta \f$).  Reads what `in` points at: density, pressure, sound speed, P/rho^2,
/// positions and velocities one array per axis.  Without \p track_signal the loop has no trace
/// of the signal velocity (the time step of eq 7 does not need it).  When a term takes sums in
/// the force pass (terms.hpp, PairSum), each particle's sums go to \p sums, for the term to
/// finish after the pass; a scene without such a term has no trace of them in its loop.  Only
/// the particles of \p active are computed (all by default; with individual time steps, those
/// whose step ends now), each exactly as in a pass over all.
template <int D, class K, class TermList, bool evolve_energy, bool track_signal = false>
void compute_forces(Particles<D>& p, const NeighbourList<D>& list, const ParticleView<D>& in,
                    const TermList& terms, DerivedFields<D>& fields, double signal_beta = 0.0,
                    std::vector<PairSum>* sums = nullptr, ActiveSet active = {}) {
  const std::size_t n = p.size();
  constexpr bool tracks_mu = TermList::tracks_mu;
  constexpr bool extra = TermList::template any_pair_acceleration<D>;
  constexpr bool with_sum = TermList::template any_force_sum<D>;
  if constexpr (tracks_mu) fields.max_mu.resize(n);
  if constexpr (track_signal) fields.max_signal.resize(n);
  if constexpr (with_sum) {
    require(sums != nullptr,
            "force pass: a term takes sums in the force pass, but no place for "
            "them was given (the sums argument of compute_forces)");
    sums->resize(n);
  }
  const std::size_t count_active = active.size(n);
  // (chunks of 512 particles; of 64 for a subset, which is often small)
  const int chunk = active.all() ? 512 : 64;
#pragma omp parallel for schedule(dynamic, chunk) if (n >= parallel_threshold)
  for (std::size_t k_active = 0; k_active < count_active; ++k_active) {
    const std::size_t i = active[k_active];
    const ParticleView<D> local = in;  // a private copy: its pointers stay in registers
    const std::span<const Neighbour> nb = list.of(i);
    const auto count = static_cast<std::ptrdiff_t>(nb.size());
    double a0 = 0, a1 = 0, a2 = 0, energy_rate = 0, max_mu = 0, max_signal = 0;
    double s0 = 0, s1 = 0, s2 = 0, s3 = 0;  // a term's force-pass sums (if any)
#pragma omp simd simdlen(8) if(simd : D > 1) reduction(+ : a0, a1, a2, energy_rate) \
    reduction(max : max_mu, max_signal) reduction(+ : s0, s1, s2, s3)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const auto pf = pair_force<D, K, TermList, track_signal>(
          local, terms, i, nb[static_cast<std::size_t>(k)], signal_beta);
      a0 -= pf.f * pf.r_ij[0];
      if constexpr (D > 1) a1 -= pf.f * pf.r_ij[1];
      if constexpr (D > 2) a2 -= pf.f * pf.r_ij[2];
      if constexpr (evolve_energy) {
        if constexpr (TermList::template any_heating<D>) {
          energy_rate += pf.f_heat * pf.rv;
        } else {
          energy_rate += 0.5 * pf.f * pf.rv;
        }
      }
      if constexpr (extra) {
        a0 += pf.extra.a[0];
        if constexpr (D > 1) a1 += pf.extra.a[1];
        if constexpr (D > 2) a2 += pf.extra.a[2];
        if constexpr (evolve_energy) energy_rate += pf.extra.heat;
      }
      if constexpr (tracks_mu) max_mu = std::max(max_mu, pf.mu);
      if constexpr (track_signal) max_signal = std::max(max_signal, pf.signal);
      if constexpr (with_sum) {
        s0 += pf.sum.s[0];
        s1 += pf.sum.s[1];
        s2 += pf.sum.s[2];
        s3 += pf.sum.s[3];
      }
    }
    const double acc[3] = {a0, a1, a2};
    for (int a = 0; a < D; ++a) p.acceleration[i][a] = acc[a];
    if constexpr (evolve_energy) p.energy_rate[i] = energy_rate;
    if constexpr (tracks_mu) fields.max_mu[i] = max_mu;
    if constexpr (track_signal) fields.max_signal[i] = max_signal;
    if constexpr (with_sum) (*sums)[i] = PairSum{{s0, s1, s2, s3}};
  }
}

}  // namespace sph
