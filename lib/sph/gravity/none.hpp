#pragma once
/// \file
/// \brief No self-gravity: the default of a scene, and the interface a gravity module implements.
///
/// Self-gravity is not a term of the force pass: it acts between every pair of particles, not
/// only between neighbours, and is computed by its own method (direct summation, a tree).  A
/// gravity module provides
///  - `add_accelerations(p, box, active)`: adds \f$ -\nabla\Phi_i \f$ to p.acceleration[i] of
///    every particle of the ActiveSet (all by default; with individual time steps, the ones
///    whose step ends now) and keeps their \f$ \Phi_i \f$;
///  - `potential_energy(p, box)`: \f$ E_\mathrm{pot} = \tfrac12\sum_i m_i \Phi_i \f$, for the
///    energy diagnostic;
/// and the step calls it after the force pass.  A scene without gravity names NoGravity, and
/// its step contains no gravity code.

#include "sph/box.hpp"
#include "sph/integration/active_set.hpp"
#include "sph/particles.hpp"

namespace sph {

/// The empty gravity module: a scene without self-gravity evaluates nothing here.
struct NoGravity {
  static constexpr const char* name = "none";
  static constexpr bool active = false;
  template <int D>
  void add_accelerations(Particles<D>&, const Box<D>&, ActiveSet = {}) {}
  template <int D>
  double potential_energy(const Particles<D>&, const Box<D>&) const {
    return 0;
  }
};

}  // namespace sph
