#pragma once
/// \file
/// \brief The force pass: momentum and energy equations in the Hernquist & Katz (1989) form.
///
/// Selhammar (1997) eq 4, read as in NOTES.md:
/// \f[ \frac{d\mathbf v_i}{dt} = -\sum_j m_j \left( \frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}
///       + \Pi_{ij} \right) \nabla_i W(r_{ij}, \bar h_{ij}), \qquad
///     \frac{du_i}{dt} = \frac12 \sum_j m_j \left( \frac{P_i}{\rho_i^2} + \frac{P_j}{\rho_j^2}
///       + \Pi_{ij} \right) \mathbf v_{ij}\cdot\nabla_i W(r_{ij}, \bar h_{ij}). \f]
/// The bracket is symmetric in i and j and the kernel gradient antisymmetric, so every pair
/// exerts equal and opposite forces: momentum is conserved to round-off, and the energy the
/// pair removes from the motion it puts into heat, shared equally.
///
/// The pass is a gather loop: particle i sums over its neighbour list and writes only its own
/// acceleration and energy rate.  Each pair is therefore evaluated twice, once from each side,
/// but the threads need no locks and the result is bitwise the same for any thread count.
///
/// What is summed is chosen at compile time: the pressure form and the viscosity are template
/// parameters, and a viscosity with `active == false` compiles to nothing.

#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/parallel.hpp"
#include "sph/pair.hpp"
#include "sph/particles.hpp"
#include "sph/viscosity/none.hpp"

#include <algorithm>
#include <array>
#include <span>
#include <vector>

namespace sph {

/// The symmetric pressure bracket of Hernquist & Katz (1989): \f$ P_i/\rho_i^2 + P_j/\rho_j^2 \f$.
struct PressureHernquistKatz {
  static constexpr const char* name = "Hernquist & Katz (1989)";
  static double bracket(double p_over_rho2_i, double p_over_rho2_j, double, double, double, double) {
    return p_over_rho2_i + p_over_rho2_j;
  }
};

/// Selhammar's eq 4 as printed: \f$ \bar P_{ij}/\bar\rho_{ij}^2 \f$.  Offered only to show what
/// the misprint does (for two equal particles it is half the Hernquist & Katz bracket, so
/// pressure forces are halved); never the default.
struct PressureAsPrinted {
  static constexpr const char* name = "Selhammar eq 4 as printed";
  static double bracket(double, double, double p_i, double p_j, double rho_i, double rho_j) {
    const double rho_bar = 0.5 * (rho_i + rho_j);
    return 0.5 * (p_i + p_j) / (rho_bar * rho_bar);
  }
};

/// Per-particle results of the force pass that are not stored in Particles.
template <int D>
struct ForceScratch {
  std::vector<double> p_over_rho2;  ///< P_i / rho_i^2, written by the equation-of-state pass
  std::vector<double> max_mu;       ///< max_j |mu_ij|, for the time step (Selhammar eq 7)
  /// Velocities one array per axis (copied at the start of the pass): the SIMD loop loads a
  /// neighbour's components from them, one lane each, as it does positions.
  PositionArrays<D> velocities;
};

/// What one pair adds to particle i: \f$ f = m_j (\ldots) g \f$ with the acceleration
/// \f$ -f\,\mathbf r_{ij} \f$ and heating \f$ \tfrac12 f\, \mathbf r_{ij}\cdot\mathbf v_{ij} \f$, and mu_ij.
/// (Plain scalars, so the compiler keeps them in registers across the SIMD lanes.)
struct PairForce {
  double f, rv, mu;
  double r_ij[3];  // the first D are used
};

/// The per-particle inputs of the force pass, as plain arrays.
template <int D>
struct ForceInputs {
  PositionView<D> x;
  std::array<const double*, D> v;  // per axis
  const double *h, *m, *rho, *pressure, *c, *p_over_rho2;
};

/// The force between particle i and one neighbour: geometry, kernel gradient at h_bar, the
/// symmetric bracket (pressure, then viscosity).
template <int D, class K, class PressureForm, class Viscosity>
inline PairForce pair_force(const ForceInputs<D>& in, [[maybe_unused]] const Viscosity& viscosity, std::size_t i,
                               const Neighbour& nb) {
  const std::size_t j = nb.index;
  Pair<D> pr;
  pr.i = i;
  pr.j = j;
  // (Component by component rather than with Eigen's dot(): Eigen's own SIMD code would stop
  // the compiler from vectorising across pairs.)
  pr.r2 = pr.rv = 0;
#pragma GCC unroll 3
  for (int a = 0; a < D; ++a) {
    pr.r_ij[a] = in.x.separation(a, i, nb);
    pr.v_ij[a] = in.v[a][i] - in.v[a][j];
    pr.r2 += pr.r_ij[a] * pr.r_ij[a];
    pr.rv += pr.r_ij[a] * pr.v_ij[a];
  }
  pr.h_bar = 0.5 * (in.h[i] + in.h[j]);
  pr.r = std::sqrt(pr.r2);
  // Pairs in the list reach 2 max(h_i, h_j); the kernel at h_bar may end sooner (the gradient
  // factor is then zero).
  pr.gradient_factor = K::gradient_factor(pr.r, pr.h_bar);
  double bracket = PressureForm::bracket(in.p_over_rho2[i], in.p_over_rho2[j], in.pressure[i], in.pressure[j],
                                         in.rho[i], in.rho[j]);
  double mu = 0;
  if constexpr (Viscosity::active) {
    const PairViscosity visc = viscosity.pair(pr, 0.5 * (in.rho[i] + in.rho[j]), 0.5 * (in.c[i] + in.c[j]));
    bracket += visc.pi;
    // Only pairs inside the kernel limit the time step.
    mu = pr.r2 < K::support * K::support * pr.h_bar * pr.h_bar ? visc.mu : 0.0;
  }
  // Equal and opposite: the factor m_j * bracket * g multiplies the antisymmetric r_ij.
  PairForce out;
  out.f = in.m[j] * bracket * pr.gradient_factor;
  out.rv = pr.rv;
  out.mu = mu;
#pragma GCC unroll 3
  for (int a = 0; a < D; ++a) out.r_ij[a] = pr.r_ij[a];
  return out;
}

/// The force pass.  Writes p.acceleration, p.energy_rate (when the gas evolves its energy)
/// and scratch.max_mu.  Needs density, pressure, sound speed and scratch.p_over_rho2, and the
/// positions one array per axis (PositionArrays).
///
/// pair_force has no branches (a pair outside the kernel at h_bar, or receding, contributes
/// exact zeros), so the compiler runs the loop over one particle's neighbours on several pairs
/// at once in SIMD registers; the sums are reduced in a fixed order, so the result does not
/// depend on the number of threads.
template <int D, class K, class PressureForm, class Viscosity, bool evolve_energy>
void compute_forces(Particles<D>& p, const NeighbourList<D>& list, const PositionView<D>& positions,
                    const Viscosity& viscosity, ForceScratch<D>& scratch) {
  const std::size_t n = p.size();
  scratch.max_mu.resize(n);
  scratch.velocities.assign(p.velocity);
  ForceInputs<D> in{positions, {}, p.smoothing_length.data(), p.mass.data(), p.density.data(),
                    p.pressure.data(), p.sound_speed.data(), scratch.p_over_rho2.data()};
  for (int a = 0; a < D; ++a) in.v[a] = scratch.velocities.axis(a);
#pragma omp parallel for schedule(dynamic, 512) if (n >= parallel_threshold)
  for (std::size_t i = 0; i < n; ++i) {
    const ForceInputs<D> local = in;  // a private copy: its pointers stay in registers
    const std::span<const Neighbour> nb = list.of(i);
    const auto count = static_cast<std::ptrdiff_t>(nb.size());
    double a0 = 0, a1 = 0, a2 = 0, energy_rate = 0, max_mu = 0;
#pragma omp simd simdlen(8) if(simd : D > 1) reduction(+ : a0, a1, a2, energy_rate) reduction(max : max_mu)
    for (std::ptrdiff_t k = 0; k < count; ++k) {
      const PairForce pf = pair_force<D, K, PressureForm>(local, viscosity, i, nb[static_cast<std::size_t>(k)]);
      a0 -= pf.f * pf.r_ij[0];
      if constexpr (D > 1) a1 -= pf.f * pf.r_ij[1];
      if constexpr (D > 2) a2 -= pf.f * pf.r_ij[2];
      if constexpr (evolve_energy) energy_rate += 0.5 * pf.f * pf.rv;
      max_mu = std::max(max_mu, pf.mu);
    }
    const double acc[3] = {a0, a1, a2};
    for (int a = 0; a < D; ++a) p.acceleration[i][a] = acc[a];
    if constexpr (evolve_energy) p.energy_rate[i] = energy_rate;
    scratch.max_mu[i] = max_mu;
  }
}

}  // namespace sph
