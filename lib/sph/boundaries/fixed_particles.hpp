#pragma once
/// \file
/// \brief Fixed boundary particles: they push on the fluid through the pair terms and never move.
///
/// The interface of a boundary policy is described in boundaries/none.hpp.

#include "sph/dimension.hpp"
#include "sph/error.hpp"
#include "sph/particles.hpp"

#include <cstddef>

namespace sph {

/// Fixed boundary particles (ParticleKind::fixed): they sit in the neighbour lists, have a
/// density and a pressure, and push on the fluid through the ordinary pair terms, but they are
/// never kicked or drifted and their accelerations do not limit the time step (Watkins et al.
/// 1996, sect. 4.1: the walls of the Poiseuille flow).
struct FixedParticles {
  static constexpr const char* name = "fixed boundary particles";
  static constexpr bool has_constraint = false;
  template <int D>
  static bool moves(std::size_t i, const Particles<D>& p) {
    return p.kind[i] == ParticleKind::fluid;
  }
  template <int D>
  void validate(const Particles<D>& p) const {
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (p.kind[i] == ParticleKind::fluid) return;
    }
    throw Error("fixed boundary particles: every particle is fixed, nothing can move");
  }
  template <int D>
  bool constrain(Vec<D>&, Vec<D>&) const {
    return true;
  }
};

}  // namespace sph
