#pragma once
/// \file
/// \brief The Evrard (1988) collapse: a cold gas sphere with \f$ \rho \propto 1/r \f$, at rest,
/// falling in under its own gravity (Selhammar 1997, sect. 5.3 and eq 27).
///
/// \f[ \rho(r) = \frac{M}{2\pi R^2 r} \quad (r < R), \qquad u = 0.05\,\frac{GM}{R},
///     \qquad \gamma = 5/3, \qquad G = M = R = 1. \f]
/// The mass inside r is \f$ M(<r) = M r^2/R^2 \f$, the potential energy
/// \f$ W = -\tfrac23 GM^2/R \f$, the thermal energy \f$ uM = 0.05 \f$: the virial ratio
/// \f$ 2E_\mathrm{th}/|W| = 0.15 \f$, far from equilibrium, so the sphere falls in, its centre
/// first (the free-fall time \f$ \propto \rho^{-1/2} \f$ is shortest there).  The infall is
/// supersonic, a shock forms near the centre and moves out through the infalling gas, and the
/// sphere settles into a hot core in virial equilibrium after a bounce.
///
/// **The particles.**  Selhammar places 8192 particles "on a slightly disturbed cubic centred
/// grid" and stretches it to the 1/r profile.  We take the body-centred lattice of chapter 5's
/// homologous sphere (the N lattice points nearest the centre, each coordinate moved by up to
/// `disturbance` of the spacing) and move each point along its own ray: the point of rank k in
/// radius goes to the radius that encloses the mass fraction \f$ (k + \tfrac12)/N \f$,
/// \f$ r_k = R\sqrt{(k + 1/2)/N} \f$.  For a uniform sphere the rank already places a point at
/// \f$ r_0 \approx R[(k + 1/2)/N]^{1/3} \f$, so this is the usual stretch
/// \f$ r = r_0^{3/2}/R^{1/2} \f$, but with the radial mass profile exact shell by shell rather
/// than with the lattice's shell-to-shell noise.  The directions keep the lattice's local
/// order; the stretch makes the spacing grow as \f$ r^{1/3} \f$ outwards, anisotropically (the
/// radial spacing grows faster than the tangential one).

#include "sph/error.hpp"
#include "sph/particles.hpp"
#include "sph/setups/initial_conditions.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

namespace sph {

/// The parameters of the Evrard sphere (mass, radius, G, u, gamma, particle count, lattice
/// disturbance) and the particles they make.
struct EvrardSetup {
  int particles = 8192;
  double radius = 1.0, mass = 1.0, G = 1.0;
  double u = 0.05;  ///< specific thermal energy, in units of GM/R
  double gamma = 5.0 / 3.0;
  double disturbance =
      0.05;  ///< each lattice coordinate moved by up to this fraction of the spacing
  unsigned long seed = 1988;

  double density(double r) const { return mass / (2.0 * std::numbers::pi * radius * radius * r); }
  /// \f$ W = -\tfrac23 GM^2/R \f$ of the continuous sphere.
  double potential_energy() const { return -2.0 / 3.0 * G * mass * mass / radius; }
  double thermal_energy() const { return u * mass; }
  /// The free-fall time of the mean density, \f$ t_\mathrm{ff} = \frac{\pi}{2}
  /// \sqrt{R^3/(2GM)} \f$ = 1.11 in these units.
  double free_fall_time() const {
    return 0.5 * std::numbers::pi * std::sqrt(radius * radius * radius / (2.0 * G * mass));
  }
};

/// The particles of the Evrard sphere, centred on the origin, at rest.
inline Particles<3> make_evrard_sphere(const EvrardSetup& s) {
  require(
      s.particles >= 16 && s.particles <= 50'000'000,
      "Evrard sphere: the particle count must lie in [16, 5e7] (got " + show(s.particles) + ")");
  require(std::isfinite(s.radius) && s.radius > 0 && std::isfinite(s.mass) && s.mass > 0,
          "Evrard sphere: radius and mass must be positive and finite");
  require(std::isfinite(s.u) && s.u >= 0,
          "Evrard sphere: the thermal energy u must be finite and >= 0 (got " + show(s.u) + ")");
  require(std::isfinite(s.gamma) && s.gamma > 1,
          "Evrard sphere: gamma must exceed 1 (got " + show(s.gamma) + ")");
  require(s.disturbance >= 0 && s.disturbance < 0.5,
          "Evrard sphere: the disturbance must lie in [0, 0.5) of the spacing");
  // The uniform lattice ball of unit radius, its points in order of their distance.
  const std::vector<Vec<3>> points =
      disturbed_lattice_ball(s.particles, 1.0, s.disturbance, s.seed);
  // Each kept point along its ray to the radius of its mass rank.
  std::vector<Vec<3>> kept(s.particles);
  for (int k = 0; k < s.particles; ++k) {
    const Vec<3>& x = points[k];
    const double r0 = x.norm();
    const double r = s.radius * std::sqrt((k + 0.5) / s.particles);
    // (a lattice point exactly at the centre has no ray: give it one)
    kept[k] = r0 > 0 ? Vec<3>(x * (r / r0)) : Vec<3>(r, 0, 0);
  }
  return make_particles<3>(kept, s.mass / s.particles, s.u);
}

}  // namespace sph
