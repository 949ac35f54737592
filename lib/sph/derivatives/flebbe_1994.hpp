#pragma once
/// \file
/// \brief The viscous force of Flebbe, Münzel, Herold, Riffert & Ruder (1994, ApJ 431, 754):
/// the stress tensor from first derivatives, then its SPH divergence.
///
/// Watkins et al. (1996) compare their method with this one without printing its equations; we
/// use the form in which it is commonly implemented (also Sijacki & Springel 2006, eqs 7-9).
/// First the velocity gradient with the standard weights \f$ m_j/\rho_i \f$ (Watkins eq 3),
/// \f$ J_{\alpha\beta,i} = \rho_i^{-1}\sum_j m_j (v_j - v_i)_\alpha \partial_\beta W_{ij} \f$, and
/// from it the viscous stress of the Navier-Stokes equation (Watkins eq 1),
/// \f[ \sigma_{\alpha\beta} = \mu_s\left(J_{\alpha\beta} + J_{\beta\alpha} -
///       \tfrac23\delta_{\alpha\beta}\,\mathrm{tr}J\right)
///     + \mu_b\,\delta_{\alpha\beta}\,\mathrm{tr}J ; \f]
/// then its divergence in the symmetric form of the pressure force,
/// \f[ \left(\frac{d\mathbf v}{dt}\right)_i = \sum_j m_j \left(\frac{\sigma_i}{\rho_i^2} +
///       \frac{\sigma_j}{\rho_j^2}\right)\cdot\nabla_i W_{ij} , \f]
/// which conserves momentum exactly (the pair terms are equal and opposite) but, like the
/// pressure force, has a zeroth-order error: a constant stress gives
/// \f$ 2\sigma\cdot\sum_j (m_j/\rho^2)\nabla_i W_{ij} \f$, zero only where the particles are
/// ordered.  On a disordered set that error is what Fig 3c of Watkins et al. shows.
///
/// The second derivatives themselves come out by choosing the coefficients: with
/// \f$ \mu_s = 1, \mu_b = -4/3 \f$ the stress is \f$ J + J^T - 2\,\mathrm{tr}J\, I \f$ and its
/// divergence
/// \f$ \nabla^2\mathbf v - \nabla(\nabla\cdot\mathbf v) = -\nabla\times\nabla\times\mathbf v \f$
/// exactly in the continuum, for any field; with \f$ \mu_s = 0, \mu_b = 1 \f$ it is
/// \f$ \nabla(\nabla\cdot\mathbf v) \f$.

#include "sph/derivatives/particle_set.hpp"

#include <vector>

namespace sph::derivatives::flebbe {

/// The viscous acceleration \f$ \rho^{-1}\nabla\cdot\sigma \f$ of every particle, for
/// coefficients of shear and bulk viscosity \f$ \mu_s, \mu_b \f$ (constant).
template <int D, class K>
std::vector<Vec<D>> viscous_acceleration(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                                         double shear, double bulk) {
  const std::vector<Mat<D>> J = jacobian(set, v, Volume::own);
  const auto& p = set.particles();
  // sigma_i / rho_i^2 for every particle: the first pass's result, read by the second.
  std::vector<Mat<D>> s(set.size());
  for (std::size_t i = 0; i < s.size(); ++i) {
    const double div = J[i].trace();
    const Mat<D> stress =
        shear * (J[i] + J[i].transpose()) + ((bulk - 2.0 / 3.0 * shear) * div) * Mat<D>::Identity();
    s[i] = stress / (p.density[i] * p.density[i]);
  }
  std::vector<Vec<D>> out(set.size());
  set.each([&](std::size_t i) {
    Vec<D> sum = Vec<D>::Zero();
    set.pairs(i, [&](std::size_t j, const Vec<D>&, const Vec<D>& grad) {
      sum += p.mass[j] * ((s[i] + s[j]) * grad);
    });
    out[i] = sum;
  });
  return out;
}

/// \f$ \nabla\times\nabla\times\mathbf v = -\rho\,\times \f$ the acceleration with
/// \f$ \mu_s = 1, \mu_b = -4/3 \f$.
template <int D, class K>
std::vector<Vec<D>> curl_curl(const ParticleSet<D, K>& set, std::span<const Vec<D>> v) {
  std::vector<Vec<D>> a = viscous_acceleration(set, v, 1.0, -4.0 / 3.0);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] *= -set.particles().density[i];
  return a;
}

/// \f$ \nabla(\nabla\cdot\mathbf v) = \rho\,\times \f$ the acceleration with
/// \f$ \mu_s = 0, \mu_b = 1 \f$.
template <int D, class K>
std::vector<Vec<D>> grad_div(const ParticleSet<D, K>& set, std::span<const Vec<D>> v) {
  std::vector<Vec<D>> a = viscous_acceleration(set, v, 0.0, 1.0);
  for (std::size_t i = 0; i < a.size(); ++i) a[i] *= set.particles().density[i];
  return a;
}

}  // namespace sph::derivatives::flebbe
