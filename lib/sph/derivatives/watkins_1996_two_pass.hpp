#pragma once
/// \file
/// \brief Second derivatives of a velocity field by applying a first derivative twice
/// (Watkins, Bhattal, Francis, Turner & Whitworth 1996, eqs 4-6).
///
/// The first pass gives, at every particle, the velocity gradient with the neighbour's volume
/// \f$ m_j/\rho_j \f$ (particle_set.hpp), and from it the curl (eq 4) and the divergence (eq 6).
/// The second pass differentiates those fields in the same way (eq 5):
/// \f[ (\nabla\times\nabla\times\mathbf v)_i = \sum_j \frac{m_j}{\rho_j}
///       \left[(\nabla\times\mathbf v)_i - (\nabla\times\mathbf v)_j\right]\times\nabla_i W_{ij},
///     \qquad
///     (\nabla(\nabla\cdot\mathbf v))_i = \sum_j \frac{m_j}{\rho_j}
///       \left[(\nabla\cdot\mathbf v)_j - (\nabla\cdot\mathbf v)_i\right]\nabla_i W_{ij}, \f]
/// and the Laplacian is their difference, \f$ \nabla^2\mathbf v = \nabla(\nabla\cdot\mathbf v) -
/// \nabla\times\nabla\times\mathbf v \f$.  The second pass needs the first field at every
/// neighbour, so the two cannot be fused into one loop: every particle's first derivative must
/// be finished before any particle's second begins.  Both passes run over the same neighbour
/// list.
///
/// Why the neighbour's volume.  Write \f$ A_j - A_i \f$ as a Taylor series about i.  The sum
/// \f$ \sum_j V_{ij} (A_j - A_i) \nabla_i W_{ij} \f$ has no zeroth-order error -- a constant field
/// gives exactly zero, however disordered the particles -- and its first-order term is
/// \f$ \partial_\gamma A \sum_j V_{ij} (\mathbf r_j - \mathbf r_i)_\gamma \nabla_i W_{ij} \f$,
/// correct where that moment matrix is the identity.  With \f$ V_{ij} = m_j/\rho_j \f$ the matrix
/// is the SPH estimate of \f$ \int (\mathbf r' - \mathbf r)\otimes\nabla W\, dV' = I \f$ with
/// each neighbour carrying its own volume: where particles crowd, each weighs less.  With
/// \f$ m_j/\rho_i \f$ every neighbour carries the volume of particle i, and a local excess of
/// neighbours becomes an error of the derivative.  Chapter 7 measures the difference.

#include "sph/derivatives/particle_set.hpp"

#include <vector>

namespace sph::derivatives {

/// The curl of every particle's velocity (first pass, eq 4).
template <int D, class K>
std::vector<Curl<D>> curls(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                           Volume volume = Volume::neighbour) {
  const std::vector<Mat<D>> J = jacobian(set, v, volume);
  std::vector<Curl<D>> out(J.size());
  for (std::size_t i = 0; i < J.size(); ++i) out[i] = curl<D>(J[i]);
  return out;
}

/// The divergence of every particle's velocity (first pass, eq 6).
template <int D, class K>
std::vector<double> divergences(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                                Volume volume = Volume::neighbour) {
  const std::vector<Mat<D>> J = jacobian(set, v, volume);
  std::vector<double> out(J.size());
  for (std::size_t i = 0; i < J.size(); ++i) out[i] = divergence<D>(J[i]);
  return out;
}

/// \f$ \nabla\times\nabla\times\mathbf v \f$ by two passes (eqs 4-5).  In 2D the curl is
/// \f$ \omega\,\hat{\mathbf z} \f$ and its curl \f$ (\partial_y\omega, -\partial_x\omega) \f$.
template <int D, class K>
std::vector<Vec<D>> curl_curl(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                              Volume volume = Volume::neighbour) {
  static_assert(D == 2 || D == 3, "curl_curl: only in 2D and 3D");
  const std::vector<Curl<D>> w = curls(set, v, volume);
  std::vector<Vec<D>> out(set.size());
  if constexpr (D == 2) {
    std::vector<double> wz(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) wz[i] = w[i][0];
    const std::vector<Vec<2>> g = gradient(set, std::span<const double>(wz), volume);
    for (std::size_t i = 0; i < g.size(); ++i) out[i] = Vec<2>(g[i][1], -g[i][0]);
  } else {
    const std::vector<Mat<3>> Jw = jacobian(set, std::span<const Vec<3>>(w), volume);
    for (std::size_t i = 0; i < Jw.size(); ++i) out[i] = curl<3>(Jw[i]);
  }
  return out;
}

/// \f$ \nabla(\nabla\cdot\mathbf v) \f$ by two passes (eq 6, then eq 7 applied to it).
template <int D, class K>
std::vector<Vec<D>> grad_div(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                             Volume volume = Volume::neighbour) {
  const std::vector<double> d = divergences(set, v, volume);
  return gradient(set, std::span<const double>(d), volume);
}

/// \f$ \nabla^2\mathbf v = \nabla(\nabla\cdot\mathbf v) - \nabla\times\nabla\times\mathbf v \f$
/// (in 1D simply \f$ \nabla(\nabla\cdot\mathbf v) \f$).
template <int D, class K>
std::vector<Vec<D>> laplacian(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                              Volume volume = Volume::neighbour) {
  std::vector<Vec<D>> out = grad_div(set, v, volume);
  if constexpr (D > 1) {
    const std::vector<Vec<D>> cc = curl_curl(set, v, volume);
    for (std::size_t i = 0; i < out.size(); ++i) out[i] -= cc[i];
  }
  return out;
}

}  // namespace sph::derivatives
