#pragma once
/// \file
/// \brief A set of particles frozen in place, and the one loop every SPH derivative is made of.
///
/// An SPH derivative of a field \f$ A \f$ at particle i is a sum over i's neighbours of a
/// difference of the field times the kernel gradient, weighted by a volume:
/// \f[ (\partial_\beta A)_i \approx \sum_j V_{ij}\, (A_j - A_i)\, \partial_{\beta} W_{ij},
///     \qquad \nabla_i W_{ij} = \nabla_i W(|\mathbf r_i - \mathbf r_j|, \bar h_{ij}). \f]
/// The methods of chapter 7 differ only in what they difference and which volume they use:
///  - \f$ V_{ij} = m_j/\rho_j \f$, the volume of the *neighbour* (Watkins et al. 1996, eq 4);
///  - \f$ V_{ij} = m_j/\rho_i \f$, the standard form \f$ \rho_i^{-1} \sum_j m_j \ldots \f$
///    (their eq 3; Monaghan 1992), which Flebbe et al. (1994) use for their first derivatives.
///
/// ParticleSet holds what these sums read (positions one array per axis with the box's periodic
/// images, masses, smoothing lengths, densities, the neighbour list) and runs the pair loop.
/// It reads the densities the caller computed -- with the self term or without, gather or
/// pair-averaged -- so that a chapter can show what each choice does to the derivatives.
/// Nothing here moves a particle: the moving term is lib/sph/terms/watkins_1996.hpp.

#include "sph/box.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/kernel.hpp"
#include "sph/neighbours/neighbour_list.hpp"
#include "sph/parallel.hpp"
#include "sph/particles.hpp"

#include <cmath>
#include <cstddef>
#include <span>
#include <vector>

namespace sph::derivatives {

/// A D x D matrix: the velocity gradient
/// \f$ J_{\alpha\beta} = \partial v_\alpha/\partial x_\beta \f$.
template <int D>
using Mat = Eigen::Matrix<double, D, D>;

/// The volume each neighbour's difference is weighted with.
enum class Volume {
  neighbour,  ///< \f$ m_j/\rho_j \f$ (Watkins et al. 1996, eq 4)
  own,        ///< \f$ m_j/\rho_i \f$ (the standard form, their eq 3)
};

/// Particles frozen in place, with their densities and a neighbour list built for them.
template <int D, class K = Kernel<D>>
class ParticleSet {
 public:
  /// The set reads `p` and `list` where they are (both must outlive it) and copies the
  /// positions one array per axis.  The densities must already be positive and finite.
  ParticleSet(const Particles<D>& p, const NeighbourList<D>& list, const Box<D>& box)
      : p_(p), list_(list) {
    require(list.particles() == p.size(), "derivatives: the neighbour list is for another set");
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (!(std::isfinite(p.density[i]) && p.density[i] > 0)) {
        throw Error("derivatives: particle " + show(i) + " has density " + show(p.density[i]) +
                    " (compute the densities first)");
      }
    }
    positions_.assign(p.position);
    x_ = positions_.view(box);
  }

  std::size_t size() const { return p_.size(); }
  const Particles<D>& particles() const { return p_; }
  const NeighbourList<D>& list() const { return list_; }

  /// The weight \f$ V_{ij} \f$ of neighbour j in a sum for particle i.
  double volume(std::size_t i, std::size_t j, Volume v) const {
    return p_.mass[j] / (v == Volume::neighbour ? p_.density[j] : p_.density[i]);
  }

  /// Calls `f(j, r_ij, grad_i W_ij)` for every neighbour j of particle i, with
  /// \f$ \mathbf r_{ij} = \mathbf r_i - \mathbf r_j \f$ (nearest periodic image) and the kernel
  /// gradient at \f$ \bar h_{ij} = (h_i + h_j)/2 \f$.  Pairs beyond the kernel's reach at
  /// \f$ \bar h_{ij} \f$ (the list reaches \f$ 2\max(h_i, h_j) \f$) have a zero gradient and are
  /// skipped.
  template <class F>
  void pairs(std::size_t i, F&& f) const {
    const double* h = p_.smoothing_length.data();
    for (const Neighbour& n : list_.of(i)) {
      Vec<D> r_ij;
      for (int a = 0; a < D; ++a) r_ij[a] = x_.separation(a, i, n);
      const double g = K::gradient_factor(r_ij.norm(), 0.5 * (h[i] + h[n.index]));
      if (g != 0) f(n.index, r_ij, Vec<D>(g * r_ij));
    }
  }

  /// Calls `f(i)` for every particle, in parallel (each i writes only its own result).
  template <class F>
  void each(F&& f) const {
    const std::size_t n = size();
#pragma omp parallel for schedule(dynamic, 256) if (n >= parallel_threshold)
    for (std::size_t i = 0; i < n; ++i) f(i);
  }

 private:
  const Particles<D>& p_;
  const NeighbourList<D>& list_;
  PositionArrays<D> positions_;
  PositionView<D> x_;
};

// --- first derivatives: one pass ----------------------------------------------------------

/// \f$ (\nabla f)_i = \sum_j V_{ij} (f_j - f_i) \nabla_i W_{ij} \f$ (Watkins et al. eq 7 with
/// the neighbour's volume).
template <int D, class K>
std::vector<Vec<D>> gradient(const ParticleSet<D, K>& set, std::span<const double> f,
                             Volume volume = Volume::neighbour) {
  require(f.size() == set.size(), "gradient: one value per particle");
  std::vector<Vec<D>> out(set.size());
  set.each([&](std::size_t i) {
    Vec<D> sum = Vec<D>::Zero();
    set.pairs(i, [&](std::size_t j, const Vec<D>&, const Vec<D>& grad) {
      sum += set.volume(i, j, volume) * (f[j] - f[i]) * grad;
    });
    out[i] = sum;
  });
  return out;
}

/// The velocity gradient \f$ J_{\alpha\beta} = \sum_j V_{ij} (v_j - v_i)_\alpha
/// (\nabla_i W_{ij})_\beta \f$.  Its trace is Watkins' eq 6 and its antisymmetric part eq 4:
/// every first derivative of v comes from this one sum.
template <int D, class K>
std::vector<Mat<D>> jacobian(const ParticleSet<D, K>& set, std::span<const Vec<D>> v,
                             Volume volume = Volume::neighbour) {
  require(v.size() == set.size(), "jacobian: one vector per particle");
  std::vector<Mat<D>> out(set.size());
  set.each([&](std::size_t i) {
    Mat<D> sum = Mat<D>::Zero();
    set.pairs(i, [&](std::size_t j, const Vec<D>&, const Vec<D>& grad) {
      sum += set.volume(i, j, volume) * (v[j] - v[i]) * grad.transpose();
    });
    out[i] = sum;
  });
  return out;
}

/// \f$ \nabla\cdot\mathbf v = \mathrm{tr}\, J \f$.
template <int D>
double divergence(const Mat<D>& J) {
  return J.trace();
}

/// Components of a curl: one (the z-component) in 2D, three in 3D.
template <int D>
using Curl = Eigen::Matrix<double, D == 2 ? 1 : 3, 1>;

/// \f$ \nabla\times\mathbf v \f$ from the velocity gradient: in 3D
/// \f$ (J_{zy} - J_{yz}, J_{xz} - J_{zx}, J_{yx} - J_{xy}) \f$, in 2D its z-component.
template <int D>
Curl<D> curl(const Mat<D>& J) {
  static_assert(D == 2 || D == 3, "curl: only in 2D and 3D");
  if constexpr (D == 2) {
    return Curl<2>(J(1, 0) - J(0, 1));
  } else {
    return Curl<3>(J(2, 1) - J(1, 2), J(0, 2) - J(2, 0), J(1, 0) - J(0, 1));
  }
}

}  // namespace sph::derivatives
