#pragma once
/// \file
/// \brief No external potential: the default of a scene, and the interface every external
/// potential implements.
///
/// An external potential \f$ \Phi(\mathbf r) \f$ acts on each particle by itself, not through the
/// neighbour list: it is not a term of the force pass but a module of its own, called after
/// it.  It provides
///  - `acceleration(x)`: \f$ -\nabla\Phi(\mathbf x) \f$, added to every moving particle;
///  - `potential(x)`: \f$ \Phi(\mathbf x) \f$, for the energy diagnostic
///    (\f$ E_\mathrm{pot} = \sum_i m_i \Phi(\mathbf r_i) \f$);
///  - `timestep(x, courant)` and `timestep_name`: its own limit on the step (inf for none).

#include "sph/dimension.hpp"

#include <limits>

namespace sph {

/// The empty external potential: no acceleration, no energy, no limit on the time step.
struct NoExternalPotential {
  static constexpr const char* name = "none";
  static constexpr bool active = false;
  static constexpr const char* timestep_name = "none";
  template <int D>
  Vec<D> acceleration(const Vec<D>&) const {
    return Vec<D>::Zero();
  }
  template <int D>
  double potential(const Vec<D>&) const {
    return 0;
  }
  template <int D>
  double timestep(const Vec<D>&, double) const {
    return std::numeric_limits<double>::infinity();
  }
};

}  // namespace sph
