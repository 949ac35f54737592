#pragma once
/// \file
/// \brief The pressure force with the "grad-h" correction \f$ \Omega_i \f$ of Springel &
/// Hernquist (2002) and Price (2012): the terms that a smoothing length tied to the density
/// adds to the equations of motion.
///
/// When h follows the density, \f$ h_i \propto (m_i/\rho_i)^{1/D} \f$, the Lagrangian
/// derivation of SPH gives each particle's pressure term a factor \f$ 1/\Omega_i \f$,
/// \f[ \frac{d\mathbf v_i}{dt} = -\sum_j m_j \left( \frac{P_i}{\Omega_i\rho_i^2}
///       + \frac{P_j}{\Omega_j\rho_j^2} \right) \nabla_i W_{ij}, \qquad
///     \Omega_i = 1 - \frac{\partial h_i}{\partial\rho_i} \sum_j m_j
///       \frac{\partial W(r_{ij}, h_i)}{\partial h_i}
///     = 1 + \frac{h_i}{D\rho_i} \sum_j m_j \frac{\partial W(r_{ij}, h_i)}{\partial h_i}, \f]
/// the sum over the neighbours and the particle itself.  For the M4 kernel in D dimensions,
/// \f$ \partial W/\partial h = -(D\,W + r\,\partial W/\partial r)/h \f$.
///
/// What it does on a lattice (chapter 4, Step 6): in 1D the sum above is
/// \f$ -(\rho/h)(S_\rho - S) \f$, with \f$ S_\rho \f$ the lattice's density sum and S its
/// gradient sum, so \f$ \Omega = S/S_\rho \f$: dividing by it takes out of every pressure force
/// the gradient sum's bias, 2.2 % at \f$ h = 1.2\Delta x \f$, and leaves the density sum's,
/// which the shock tube's mass calibration has removed.  At \f$ h = \Delta x \f$ both sums are
/// exactly one and \f$ \Omega = 1 \f$.
///
/// This term is the correction alone, inside our pair-averaged scheme: the kernel gradient of
/// the force pass stays at \f$ \bar h_{ij} \f$ and the density is Selhammar's pair-averaged
/// sum, so it is the full grad-h scheme where h is uniform and an approximation of it where h
/// varies.  It is a bracket term (terms.hpp) -- central, symmetric, conserving momentum and
/// energy by construction -- with a gradient pass of its own for the sum, and it is written
/// for the M4 kernel (sph::Kernel<D>).

#include "sph/fields.hpp"
#include "sph/kernel.hpp"
#include "sph/pair.hpp"
#include "sph/terms.hpp"

#include <limits>
#include <vector>

namespace sph {

/// The pressure term with the grad-h factor: its gradient pass sums \f$ \Omega_i \f$, its
/// bracket divides each particle's \f$ P/\rho^2 \f$ by it.
struct PressureGradH {
  static constexpr const char* name = "pressure with the grad-h correction (Springel & Hernquist)";

  std::vector<double> omega;              ///< \f$ \Omega_i \f$
  std::vector<double> p_over_omega_rho2;  ///< \f$ P_i/(\Omega_i\rho_i^2) \f$

  void resize(std::size_t n) {
    omega.assign(n, 1.0);
    p_over_omega_rho2.assign(n, 0.0);
  }

  /// \f$ \partial W(r, h)/\partial h \f$ of the M4 kernel.
  template <int D>
  static double dw_dh(double r, double h) {
    return -(D * Kernel<D>::value(r, h) + r * Kernel<D>::derivative(r, h)) / h;
  }

  /// What the gradient pass sums for particle i.
  template <int D>
  struct GradientSum {
    double total = 0;  ///< \f$ \sum_j m_j \partial W(r_{ij}, h_i)/\partial h_i \f$
  };
  template <int D>
  void gradient_pair(GradientSum<D>& sum, const Pair<D>& p, const ParticleView<D>& in) const {
    sum.total += in.m[p.j] * dw_dh<D>(p.r, in.h[p.i]);
  }
  template <int D>
  void gradient_finish(std::size_t i, GradientSum<D>& sum, const ParticleView<D>& in) {
    const double h = in.h[i];
    const double total = sum.total + in.m[i] * dw_dh<D>(0.0, h);  // (the particle itself)
    omega[i] = 1.0 + h / (D * in.rho[i]) * total;
    // (Omega <= 0 only with far too few neighbours: the NaN stops the step at the force check,
    // which names the particle; a throw inside the parallel pass could not be caught)
    p_over_omega_rho2[i] =
        omega[i] > 0 ? in.p_over_rho2[i] / omega[i] : std::numeric_limits<double>::quiet_NaN();
  }

  /// \f$ P_i/(\Omega_i\rho_i^2) + P_j/(\Omega_j\rho_j^2) \f$.
  template <int D>
  Bracket bracket(const Pair<D>& pair, const ParticleView<D>&) const {
    return {p_over_omega_rho2[pair.i] + p_over_omega_rho2[pair.j], 0.0};
  }
};

}  // namespace sph
