#pragma once
/// \file
/// \brief The particle sets of the static tests of Watkins et al. (1996, §3): N particles in a
/// periodic unit box, equal masses for a mean density of one, one constant h for a given
/// expected neighbour number; random ("unsettled") or settled to uniform density.
///
/// Chapter 2 builds and measures these sets; chapter 7 differentiates velocity fields on them.
///
/// **The constant h** (their Appendix A, eqs A5-A7): the mass within the kernel's radius 2h is
/// \f$ N_\mathrm{kernel}\, m \f$, so \f$ h = \tfrac12 (N_\mathrm{kernel}\, m / V_D \rho)^{1/D} \f$
/// with \f$ V_D \f$ the volume of the unit ball -- in 3D \f$ h = (3 m N_\mathrm{kernel}/
/// 32\pi\rho)^{1/3} \f$ (eq A6), in 2D \f$ h = (m N_\mathrm{kernel}/4\pi\sigma)^{1/2} \f$ (eq A7).

#include "sph/box.hpp"
#include "sph/density.hpp"
#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/neighbours.hpp"
#include "sph/particles.hpp"
#include "sph/setups/initial_conditions.hpp"
#include "sph/setups/relax.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numbers>
#include <vector>

namespace sph::setups {

/// Watkins' constant h for particles of mass m at density rho with N_kernel expected
/// neighbours within 2h (eqs A6-A7, in D dimensions).
template <int D>
double watkins_smoothing_length(double mass, double neighbours, double density) {
  require(mass > 0 && neighbours > 0 && density > 0 && std::isfinite(mass * neighbours / density),
          "watkins_smoothing_length: mass, neighbour number and density must be positive");
  return 0.5 * root<D>(neighbours * mass / (unit_ball_volume<D>() * density));
}

/// The periodic unit box of the static tests.
template <int D>
Box<D> unit_box() {
  return Box<D>::periodic_box(Vec<D>::Zero(), Vec<D>::Ones());
}

/// Particles at `positions` in the unit box, equal masses 1/N (mean density one), at rest, and
/// Watkins' constant h for `neighbours` expected neighbours.
template <int D>
Particles<D> unit_box_particles(const std::vector<Vec<D>>& positions, double neighbours) {
  require(!positions.empty(), "unit_box_particles: no positions");
  const double mass = 1.0 / static_cast<double>(positions.size());
  Particles<D> p = make_particles<D>(positions, mass);
  std::fill(p.smoothing_length.begin(), p.smoothing_length.end(),
            watkins_smoothing_length<D>(mass, neighbours, 1.0));
  return p;
}

/// The random set of Fig 3: n points uniform in the box (a Poisson set), constant h.
template <int D>
Particles<D> watkins_random_set(std::size_t n, double neighbours, std::uint64_t seed) {
  return unit_box_particles<D>(uniform_random<D>(Vec<D>::Zero(), Vec<D>::Ones(), n, seed),
                               neighbours);
}

/// The settled set of Fig 1: the random set relaxed to uniform density (relax.hpp, pressure
/// \f$ \propto \rho^\gamma \f$), constant h.  Its densities (gather, self term included) are
/// those of the returned particles.
template <int D>
Particles<D> watkins_settled_set(std::size_t n, double neighbours, std::uint64_t seed,
                                 double gamma = 2.0, RelaxReport* report = nullptr) {
  Particles<D> p = watkins_random_set<D>(n, neighbours, seed);
  RelaxOptions options;
  options.gamma = gamma;
  const RelaxReport r = relax_to_uniform_density(p, unit_box<D>(), options);
  if (report) *report = r;
  return p;
}

/// The velocity field of the static tests (eq 12): \f$ v_x = \sin 2\pi y \f$, the others zero,
/// so that \f$ \nabla\times\nabla\times\mathbf v = (4\pi^2\sin 2\pi y, 0, 0) \f$ and
/// \f$ \nabla(\nabla\cdot\mathbf v) = 0 \f$ (eqs 13-14).  With `noise` > 0, an independent
/// uniform random number in [-noise, noise] is added to every component of every velocity (the
/// noisy field of Fig 2, whose amplitude the paper does not give).
template <int D>
std::vector<Vec<D>> watkins_shear_field(const Particles<D>& p, double noise = 0,
                                        std::uint64_t seed = 11) {
  static_assert(D >= 2, "watkins_shear_field: v_x depends on y");
  require(std::isfinite(noise) && noise >= 0, "watkins_shear_field: the noise must be >= 0");
  std::vector<Vec<D>> v(p.size(), Vec<D>::Zero());
  for (std::size_t i = 0; i < p.size(); ++i)
    v[i][0] = std::sin(2 * std::numbers::pi * p.position[i][1]);
  if (noise > 0) disturb(v, noise, seed);
  return v;
}

/// A compressive field beside it: \f$ v_x = \sin 2\pi x \f$, with
/// \f$ \nabla(\nabla\cdot\mathbf v) = (-4\pi^2\sin 2\pi x, 0, 0) \f$ and no curl.
template <int D>
std::vector<Vec<D>> compression_field(const Particles<D>& p) {
  std::vector<Vec<D>> v(p.size(), Vec<D>::Zero());
  for (std::size_t i = 0; i < p.size(); ++i)
    v[i][0] = std::sin(2 * std::numbers::pi * p.position[i][0]);
  return v;
}

}  // namespace sph::setups
