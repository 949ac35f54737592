#pragma once
/// \file
/// \brief The Laplacian of Brookshaw (1985, Proc. Astron. Soc. Australia 6, 207) from the
/// kernel's radial derivative, in one pass.
///
/// \f[ (\nabla^2\mathbf v)_i = 2\sum_j \frac{m_j}{\rho_j}\,(\mathbf v_i - \mathbf v_j)\,
///       \frac{\mathbf r_{ij}\cdot\nabla_i W_{ij}}{r_{ij}^2 + \eta^2 \bar h_{ij}^2},
///     \qquad \eta^2 = 0.01 . \f]
/// Why it works: with \f$ \mathbf s = \mathbf r_j - \mathbf r_i \f$, expand
/// \f$ \mathbf v_i - \mathbf v_j = -s_\gamma\partial_\gamma\mathbf v - \tfrac12 s_\gamma s_\delta
/// \partial_\gamma\partial_\delta\mathbf v - \ldots \f$.  The weight is
/// \f$ \mathbf r_{ij}\cdot\nabla_i W_{ij}/r_{ij}^2 = W'(r)/r \f$, even in \f$ \mathbf s \f$, so the
/// first-order term averages to zero over a symmetric neighbourhood, and the second-order term
/// integrates to \f$ -\tfrac12\,\partial_\gamma\partial_\delta\mathbf v\,(\delta_{\gamma\delta}/D)
/// \int s\,W'(s)\, dV = \tfrac12\nabla^2\mathbf v \f$ (since \f$ \int s\,W'\,dV = -D \f$): the
/// factor 2 makes it the Laplacian.  One pass instead of two, and no first derivative to store.
///
/// What it cannot do: it gives \f$ \nabla^2\mathbf v \f$ and nothing else.  The Navier-Stokes
/// equation needs \f$ \nabla\times\nabla\times\mathbf v \f$ and
/// \f$ \nabla(\nabla\cdot\mathbf v) \f$
/// separately (with different coefficients); \f$ \nabla^2\mathbf v \f$ stands in for
/// \f$ -\nabla\times\nabla\times\mathbf v \f$ only where \f$ \nabla\cdot\mathbf v = 0 \f$.
/// Its first-order term vanishes only on average: on a disordered set the odd moment
/// \f$ \sum_j V_j\, \mathbf r_{ij} (\mathbf r_{ij}\cdot\nabla W)/r^2 \f$ is not zero, of order
/// \f$ \delta/h \f$ for a disorder \f$ \delta \f$, and it multiplies the velocity *gradient*: an
/// error \f$ \delta\,|\nabla\mathbf v|/h \f$, which relative to a field of wavenumber k grows like
/// \f$ \delta/(kh) \f$ -- largest where the field is steepest, and larger as h shrinks.  That is
/// the noise of Figs 2d and 3d of Watkins et al.

#include "sph/derivatives/particle_set.hpp"

#include <vector>

namespace sph::derivatives::brookshaw {

/// The regularisation \f$ \eta^2 \f$ of the denominator, in units of \f$ \bar h_{ij}^2 \f$.
inline constexpr double default_eta2 = 0.01;

/// \f$ \nabla^2\mathbf v \f$ of every particle, in one pass.
template <int D, class K>
std::vector<Vec<D>> laplacian(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                              double eta2 = default_eta2) {
  require(v.size() == set.size(), "laplacian: one vector per particle");
  const auto& p = set.particles();
  std::vector<Vec<D>> out(set.size());
  set.each([&](std::size_t i) {
    Vec<D> sum = Vec<D>::Zero();
    set.pairs(i, [&](std::size_t j, const Vec<D>& r_ij, const Vec<D>& grad) {
      const double h_bar = 0.5 * (p.smoothing_length[i] + p.smoothing_length[j]);
      const double weight = r_ij.dot(grad) / (r_ij.squaredNorm() + eta2 * h_bar * h_bar);
      sum += set.volume(i, j, Volume::neighbour) * weight * (v[i] - v[j]);
    });
    out[i] = 2.0 * sum;
  });
  return out;
}

/// \f$ \nabla\times\nabla\times\mathbf v \f$ taken as \f$ -\nabla^2\mathbf v \f$: right only
/// where \f$ \nabla\cdot\mathbf v = 0 \f$.
template <int D, class K>
std::vector<Vec<D>> curl_curl(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                              double eta2 = default_eta2) {
  std::vector<Vec<D>> out = laplacian(set, v, eta2);
  for (auto& x : out) x = -x;
  return out;
}

}  // namespace sph::derivatives::brookshaw
