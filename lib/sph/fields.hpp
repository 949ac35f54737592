#pragma once
/// \file
/// \brief What the passes hand to the terms: every per-particle field as a plain array, and the
/// fields that exist only when a term of the scene asks for them.
///
/// Particles holds what every hydrodynamic scene has (position, velocity, mass, u, h, rho, P,
/// c, acceleration, du/dt).  A term may need more from the density loop -- the density rate
/// of the continuity equation, the velocity divergence or curl -- and says so with its
/// `needs` flags (terms.hpp); the step then sums exactly those, in the density pass beside rho,
/// and allocates nothing for the others.  A term's own fields (a smoothed velocity, a curl of a
/// curl) are members of the term itself.
///
/// A pair function or a per-particle hook reads all of it through one ParticleView: plain
/// pointers, copied into a local before a SIMD loop so that the compiler keeps them in
/// registers (see forces.hpp).  pair_geometry turns an entry of the neighbour list into the
/// Pair that every pair function sees: the force pass, the gradient pass and a term's own
/// census all build their pairs with it.

#include "sph/kernel.hpp"
#include "sph/neighbours.hpp"
#include "sph/pair.hpp"
#include "sph/particles.hpp"

#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace sph {

/// Fields the density loop can sum beside rho, on request (bit flags, combined with |).
enum class Needs : unsigned {
  nothing = 0,
  density_rate = 1,         ///< \f$ \dot\rho_i \f$ by the continuity equation
  velocity_divergence = 2,  ///< \f$ (\nabla\cdot\mathbf v)_i \f$
  velocity_curl = 4,        ///< \f$ (\nabla\times\mathbf v)_i \f$ (2D and 3D)
};
constexpr Needs operator|(Needs a, Needs b) { return Needs(unsigned(a) | unsigned(b)); }
/// Whether `set` contains every flag of `flags`.
constexpr bool has(Needs set, Needs flags) {
  return (unsigned(set) & unsigned(flags)) == unsigned(flags);
}
/// Whether `set` asks for any of the velocity-derivative fields.
constexpr bool any_velocity_field(Needs set) { return unsigned(set) != 0; }

/// Components of the curl of a velocity: none in 1D, one (the z-component) in 2D, three in 3D.
template <int D>
inline constexpr int curl_components = D == 1   ? 0
                                       : D == 2 ? 1
                                                : 3;

/// The per-particle fields that exist only when some part of the scene uses them.  An array
/// that nobody asked for stays empty.
template <int D>
struct DerivedFields {
  std::vector<double>
      p_over_rho2;  ///< \f$ P_i/\rho_i^2 \f$ (equation-of-state pass), for the pressure terms
  std::vector<double>
      max_mu;  ///< \f$ \max_j |\mu_{ij}| \f$ (force pass), for the time step of eq 7
  std::vector<double> max_signal;    ///< \f$ \max_j v_{\rm sig,ij} \f$ (force pass), Monaghan 1997
  std::vector<double> density_rate;  ///< \f$ \dot\rho_i \f$ (density pass)
  std::vector<double> velocity_divergence;  ///< \f$ (\nabla\cdot\mathbf v)_i \f$ (density pass)
  std::array<std::vector<double>, curl_components<D>>
      velocity_curl;  ///< per component (density pass)

  /// Size the velocity-derivative fields in `needs` for n particles (the others stay empty).
  /// Done before a pass hands out pointers to them, so no pointer outlives a reallocation.
  void resize(Needs needs, std::size_t n) {
    if (has(needs, Needs::density_rate)) density_rate.resize(n);
    if (has(needs, Needs::velocity_divergence)) velocity_divergence.resize(n);
    if (has(needs, Needs::velocity_curl)) {
      for (auto& component : velocity_curl) component.resize(n);
    }
  }
};

/// Every per-particle field as a plain pointer (null where the field does not exist in this
/// scene): what a term's pair functions and hooks read.
template <int D>
struct ParticleView {
  PositionView<D> x;               ///< positions one array per axis, with the box's periods
  std::array<const double*, D> v;  ///< velocities one array per axis
  const double* h = nullptr;       ///< smoothing length
  const double* m = nullptr;       ///< mass
  const double* u = nullptr;       ///< internal energy per unit mass
  const double* rho = nullptr;     ///< density
  const double* pressure = nullptr;
  const double* c = nullptr;  ///< sound speed
  const double* p_over_rho2 = nullptr;
  const double* max_mu = nullptr;
  const double* density_rate = nullptr;
  const double* divergence = nullptr;
  std::array<const double*, curl_components<D>> curl{};
  const ParticleKind* kind = nullptr;  ///< fluid or fixed boundary particle (read by walls)

  /// Component a of v_i - v_j.
  double v_ij(int a, std::size_t i, std::size_t j) const { return v[a][i] - v[a][j]; }
};

/// The geometry and kinematics of particle i and one neighbour, the kernel gradient at
/// \f$ \bar h_{ij} \f$: what every pair function sees.
template <int D, class K>
inline Pair<D> pair_geometry(const ParticleView<D>& in, std::size_t i, const Neighbour& nb) {
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
  pr.support2 = K::support * K::support * pr.h_bar * pr.h_bar;
  // Pairs in the list reach 2 max(h_i, h_j); the kernel at h_bar may end sooner (the gradient
  // factor is then zero).
  pr.gradient_factor = K::gradient_factor(pr.r, pr.h_bar);
  return pr;
}

}  // namespace sph
