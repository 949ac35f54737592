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
struct ForceScratch {
  std::vector<double> p_over_rho2;  ///< P_i / rho_i^2, written by the equation-of-state pass
  std::vector<double> max_mu;       ///< max_j |mu_ij|, for the time step (Selhammar eq 7)
};

/// Build the pair seen from particle i for neighbour n.
template <int D>
inline Pair<D> make_pair(const Particles<D>& p, const NeighbourList<D>& list, std::size_t i, const Neighbour& n) {
  Pair<D> pr;
  pr.i = i;
  pr.j = n.index;
  pr.r_ij = list.separation(p.position, i, n);
  pr.r2 = pr.r_ij.squaredNorm();
  pr.h_bar = 0.5 * (p.smoothing_length[i] + p.smoothing_length[n.index]);
  return pr;
}

/// The force pass.  Writes p.acceleration, p.energy_rate (when the gas evolves its energy)
/// and scratch.max_mu.  Needs density, pressure, sound speed and scratch.p_over_rho2.
template <int D, class K, class PressureForm, class Viscosity, bool evolve_energy>
void compute_forces(Particles<D>& p, const NeighbourList<D>& list, [[maybe_unused]] const Viscosity& viscosity,
                    ForceScratch& scratch) {
  const std::size_t n = p.size();
  scratch.max_mu.resize(n);
  const double support2 = K::support * K::support;
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
  for (std::size_t i = 0; i < n; ++i) {
    Vec<D> acceleration = Vec<D>::Zero();
    double energy_rate = 0, max_mu = 0;
    for (const Neighbour& nb : list.of(i)) {
      Pair<D> pr = make_pair<D>(p, list, i, nb);
      // Pairs in the list reach 2 max(h_i, h_j); the kernel at h_bar may end sooner.
      if (pr.r2 >= support2 * pr.h_bar * pr.h_bar) continue;
      const std::size_t j = pr.j;
      pr.r = std::sqrt(pr.r2);
      pr.gradient_factor = K::gradient_factor(pr.r, pr.h_bar);
      pr.v_ij = p.velocity[i] - p.velocity[j];
      pr.rv = pr.r_ij.dot(pr.v_ij);
      // The symmetric bracket: pressure, then viscosity.
      double bracket = PressureForm::bracket(scratch.p_over_rho2[i], scratch.p_over_rho2[j], p.pressure[i],
                                             p.pressure[j], p.density[i], p.density[j]);
      if constexpr (Viscosity::active) {
        const PairViscosity visc = viscosity.pair(pr, 0.5 * (p.density[i] + p.density[j]),
                                                  0.5 * (p.sound_speed[i] + p.sound_speed[j]));
        bracket += visc.pi;
        max_mu = std::max(max_mu, visc.mu);
      }
      // Equal and opposite: the factor m_j * bracket * g multiplies the antisymmetric r_ij.
      const double f = p.mass[j] * bracket * pr.gradient_factor;
      acceleration -= f * pr.r_ij;
      if constexpr (evolve_energy) energy_rate += 0.5 * f * pr.rv;
    }
    p.acceleration[i] = acceleration;
    if constexpr (evolve_energy) p.energy_rate[i] = energy_rate;
    scratch.max_mu[i] = max_mu;
  }
}

}  // namespace sph
