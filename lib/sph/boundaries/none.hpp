#pragma once
/// \file
/// \brief No boundaries beyond the box -- the default of a scene -- and the interface every
/// boundary policy implements: what the integrator may move, and where.
///
/// Periodic axes and free ends belong to the box (box.hpp).  Everything else is a policy with
/// three touch points in the step:
///  - **which particles move**: `moves(i, p)`, asked by the integrators and the time step;
///  - **a constraint after each drift**: `constrain(x, v)` (a reflecting wall), which returns
///    false for a particle it cannot bring back (the step then stops with `describe_failure`);
///  - **the velocity a pair sees** (Watkins et al. 1996 eqs 17 and 19: a fixed particle
///    lends its neighbour a pseudo-velocity extrapolated from that neighbour's own) -- the slot
///    the Poiseuille chapter fills, inside the pair view of its viscosity term.
///
/// A scene without boundaries names NoBoundaries and pays nothing: every particle moves, and
/// no particle kind is read.

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/particles.hpp"

#include <cstddef>

namespace sph {

/// No boundaries beyond the box: every particle is a fluid particle and moves.
struct NoBoundaries {
  static constexpr const char* name = "none";
  static constexpr bool has_constraint = false;
  template <int D>
  static constexpr bool moves(std::size_t, const Particles<D>&) {
    return true;
  }
  /// A particle marked fixed in a scene that does not allow it is a mistake in the set-up.
  template <int D>
  void validate(const Particles<D>& p) const {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.kind[i] != ParticleKind::fluid) {
        throw Error("particle " + show(i) +
                    " is a fixed boundary particle, but the scene names no boundaries that hold "
                    "fixed particles (use sph::FixedParticles)");
      }
    }
  }
  template <int D>
  bool constrain(Vec<D>&, Vec<D>&) const {
    return true;
  }
};

}  // namespace sph
