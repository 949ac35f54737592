#pragma once
/// \file
/// \brief app::unbound_gas: how much of a self-gravitating gas is no longer bound to the rest,
/// and how much of the kinetic energy it carries -- for a particle set and for a spherical
/// Lagrangian profile, so that a 3D run and a 1D calculation can be compared.
///
/// A gas element of specific kinetic energy \f$ \tfrac12|\mathbf v - \mathbf v_\mathrm{cm}|^2
/// \f$, specific internal energy u and gravitational potential \f$ \Phi \f$ is counted as
/// unbound where \f$ \tfrac12|\mathbf v - \mathbf v_\mathrm{cm}|^2 + u + \Phi > 0 \f$: with its
/// heat turned into motion (as the gas expands) it would escape.  Velocities are taken relative
/// to the centre of mass, so that a set that drifts as a whole does not count as escaping; the
/// kinetic energy of that drift is reported apart.

#include "sph/gravity/direct.hpp"
#include "sph/gravity/softening.hpp"
#include "sph/measures/diagnostics.hpp"
#include "sph/particles.hpp"
#include "sph/reference/lagrangian_1d.hpp"

#include <cstddef>
#include <vector>

namespace app {

/// Where a gas's kinetic energy sits.
struct UnboundGas {
  double kinetic = 0;          ///< the whole kinetic energy
  double bulk = 0;             ///< of the centre of mass's motion
  double mass = 0;             ///< the unbound mass
  double unbound_kinetic = 0;  ///< its kinetic energy relative to the centre of mass
};

/// The unbound gas of the particles \p p, with the potential of the others from direct
/// summation (softened with each particle's smoothing length, as the runs' gravity is; a
/// particle's own smeared-out self-potential, \f$ -\tfrac75 Gm/h \f$, left out).
inline UnboundGas unbound_gas(sph::Particles<3> p) {
  sph::DirectGravity direct;
  direct.add_accelerations(p, sph::Box<3>::open());
  const std::vector<double>& phi = direct.potential();
  const double mass = sph::total_mass(p);
  const sph::Vec<3> v_cm = sph::total_momentum(p) / mass;
  UnboundGas g;
  g.kinetic = sph::kinetic_energy(p);
  g.bulk = 0.5 * mass * v_cm.squaredNorm();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const double specific = 0.5 * (p.velocity[i] - v_cm).squaredNorm();
    const double self =
        direct.G * p.mass[i] * sph::gravity::m4_potential(0.0, p.smoothing_length[i]);
    if (specific + p.internal_energy[i] + phi[i] - self > 0) {
      g.mass += p.mass[i];
      g.unbound_kinetic += p.mass[i] * specific;
    }
  }
  return g;
}

/// The unbound gas of a spherical Lagrangian profile \p p with zone masses \p zone_mass (G = 1,
/// as the chapters' units): a shell at radius r feels \f$ \Phi = -M(<r)/r - \sum_\mathrm{outside}
/// m_j/r_j \f$, each zone taken at its centre.  The centre of mass is at rest by symmetry.
inline UnboundGas unbound_gas(const sph::LagrangianProfile& p,
                              const std::vector<double>& zone_mass) {
  const std::size_t n = p.radius.size();
  std::vector<double> outside(n + 1, 0.0);  // sum of m_j / r_j over the zones beyond
  for (std::size_t i = n; i-- > 0;) outside[i] = outside[i + 1] + zone_mass[i] / p.radius[i];
  UnboundGas g;
  for (std::size_t i = 0; i < n; ++i) {
    const double specific = 0.5 * p.velocity[i] * p.velocity[i];
    const double phi = -p.mass_coordinate[i] / p.radius[i] - outside[i + 1];
    g.kinetic += zone_mass[i] * specific;
    if (specific + p.internal_energy[i] + phi > 0) {
      g.mass += zone_mass[i];
      g.unbound_kinetic += zone_mass[i] * specific;
    }
  }
  return g;
}

}  // namespace app
