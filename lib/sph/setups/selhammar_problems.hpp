#pragma once
/// \file
/// \brief The initial conditions of Selhammar's (1997) two hydrodynamic tests: the weak shock
/// tube of sect. 5.1 (eq 20) and the homologous compression of sect. 5.2 (eqs 21-26).
///
/// **The weak shock tube.**  A \f$ 1 \times 1 \times 9 \f$ box, periodic in x and y, free at
/// both ends \f$ z = -5 \f$ and \f$ z = 4 \f$; 16384 particles of equal mass on body-centred
/// cubic lattices, 8192 in \f$ -5 \le z < -4 \f$ and 8192 in \f$ -4 \le z \le 4 \f$; total
/// mass 1, u = 0.01 everywhere, at rest, \f$ \gamma = 5/3 \f$.  The counts, the volumes and the
/// mass give densities 1/2 and 1/16 (a lattice of \f$ 16^3 \times 2 \f$ in the unit cube and
/// \f$ 8 \times 8 \times 64 \times 2 \f$ in the long part, twice as far apart).  The paper
/// prints 1/4 and 1/16, which no choice of equal masses on those counts gives;
/// WeakTubeSetup::printed_densities keeps the counts and sets the masses of each side so that
/// the densities are the printed ones (the total mass is then 3/4).  The resolution is the
/// number of cells n across the dense slab (16 in the paper): the dense slab holds
/// \f$ 2n^3 \f$ particles, the thin part the same number on a lattice of half the cells per
/// unit length, \f$ 4n^3 \f$ in all.
///
/// **The homologous compression.**  A uniform sphere, R = 1, M = 1, of 8192 particles on a
/// slightly disturbed body-centred lattice, moving inwards with \f$ \mathbf v = -V_0\mathbf r \f$,
/// \f$ V_0 = 2 \f$, so that every particle would coast to the centre at t = 0.5; u = 0.001,
/// \f$ \gamma = 5/3 \f$, no gravity, no boundary.  We take the N lattice points nearest the
/// centre, with the lattice spacing that gives each particle the volume
/// \f$ (4\pi/3)/N \f$; the sphere's edge is then within half a spacing of r = 1.

#include "sph/box.hpp"
#include "sph/error.hpp"
#include "sph/particles.hpp"
#include "sph/setups/initial_conditions.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

namespace sph {

/// Selhammar's weak shock tube (eq 20).
struct WeakTubeSetup {
  int cells = 16;     ///< n: cells across the dense slab (16: the paper's 16384 particles)
  double mass = 1.0;  ///< total mass
  double u = 0.01;    ///< internal energy per unit mass, everywhere
  double gamma = 5.0 / 3.0;
  bool printed_densities = false;  ///< the printed 1/4 and 1/16 instead of the geometry's 1/2, 1/16

  static constexpr double z_left = -5, z_interface = -4, z_right = 4;
  long particles() const { return 4L * cells * cells * cells; }
  double density_left() const { return printed_densities ? 0.25 : 0.5 * mass; }
  double density_right() const { return mass / 16; }
};

/// The particles of the weak tube: the dense slab first, then the thin part.
inline Particles<3> make_weak_tube(const WeakTubeSetup& s) {
  require(s.cells >= 2 && s.cells % 2 == 0,
          "weak tube: the cells across the dense slab must be even and at least 2 (got " +
              show(s.cells) + ")");
  require(s.mass > 0 && s.u > 0 && s.gamma > 1,
          "weak tube: mass, u and gamma - 1 must be positive");
  const int n = s.cells;
  const auto dense = lattice<3>(LatticeType::body_centred, Vec<3>(0, 0, s.z_left),
                                Vec<3>(1, 1, s.z_interface), std::array<int, 3>{n, n, n});
  const auto thin = lattice<3>(LatticeType::body_centred, Vec<3>(0, 0, s.z_interface),
                               Vec<3>(1, 1, s.z_right), std::array<int, 3>{n / 2, n / 2, 4 * n});
  std::vector<Vec<3>> points = dense;
  points.insert(points.end(), thin.begin(), thin.end());
  Particles<3> p = make_particles<3>(points, 1.0, s.u);
  const double m_dense = s.density_left() * 1.0 / double(dense.size());
  const double m_thin = s.density_right() * 8.0 / double(thin.size());
  for (std::size_t i = 0; i < p.size(); ++i) p.mass[i] = i < dense.size() ? m_dense : m_thin;
  return p;
}

/// Periodic in x and y over the unit square, open along z.
inline Box<3> weak_tube_box() {
  Box<3> box;
  box.lower = Vec<3>(0, 0, 0);
  box.upper = Vec<3>(1, 1, 1);
  box.periodic = {true, true, false};
  box.validate();
  return box;
}

/// Selhammar's homologous compression (eqs 21-22).
struct HomologousSphereSetup {
  int particles = 8192;
  double radius = 1.0, mass = 1.0;
  double v0 = 2.0;  ///< v = -v0 r / R
  double u = 0.001;
  double gamma = 5.0 / 3.0;
  double disturbance = 0.05;  ///< each coordinate moved by up to this fraction of the spacing
  unsigned long seed = 1997;

  /// Eq 22: \f$ E = \tfrac{3}{10} M V_0^2 + uM \f$ (6/5 + 0.001 for the paper's numbers).
  double total_energy() const { return 0.3 * mass * v0 * v0 + u * mass; }
  double density() const {
    return mass / (4.0 / 3.0 * std::numbers::pi * radius * radius * radius);
  }
  /// Eqs 23-26: the density and radius if all the kinetic energy became heat adiabatically,
  /// \f$ \rho' = \rho_0 (u'/u_0)^{1/(\gamma-1)} \f$ with \f$ u' = E/M \f$.
  double zeroth_order_density() const {
    return density() * std::pow(total_energy() / (mass * u), 1.0 / (gamma - 1));
  }
  double zeroth_order_radius() const {
    return std::cbrt(3 * mass / (4 * std::numbers::pi * zeroth_order_density()));
  }
};

/// The particles of the homologous sphere, centred on the origin.
inline Particles<3> make_homologous_sphere(const HomologousSphereSetup& s) {
  require(s.particles >= 16,
          "homologous sphere: need at least 16 particles (got " + show(s.particles) + ")");
  require(s.radius > 0 && s.mass > 0 && s.u > 0 && s.gamma > 1 && std::isfinite(s.v0),
          "homologous sphere: radius, mass, u and gamma - 1 must be positive, v0 finite");
  require(s.disturbance >= 0 && s.disturbance < 0.5,
          "homologous sphere: the disturbance must lie in [0, 0.5) of the spacing");
  const std::vector<Vec<3>> kept =
      disturbed_lattice_ball(s.particles, s.radius, s.disturbance, s.seed);
  Particles<3> p = make_particles<3>(kept, s.mass / s.particles, s.u);
  for (std::size_t i = 0; i < p.size(); ++i) p.velocity[i] = -s.v0 / s.radius * p.position[i];
  return p;
}

}  // namespace sph
