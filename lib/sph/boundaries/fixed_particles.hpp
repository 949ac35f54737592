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

/// Fixed boundary particles, and fluid particles that move along one axis only: the step
/// keeps only that component of every fluid particle's acceleration, so a particle that starts
/// with its velocity along the axis keeps it there and never leaves its line.  Watkins et al.
/// (1996, sect. 4.1.2) restrict their Poiseuille flow so ("the particles are restricted to moving
/// only in the x-direction") to suppress an instability of the free flow.  The acceleration
/// across the axis is the pressure and viscous force the constraint holds back; total momentum
/// along the axis is untouched.
struct FixedParticlesMovingAlong : FixedParticles {
  static constexpr const char* name = "fixed boundary particles, fluid moving along one axis";
  static constexpr bool constrains_acceleration = true;
  int axis = 0;  ///< the one axis the fluid moves along

  FixedParticlesMovingAlong() = default;
  explicit FixedParticlesMovingAlong(int along) : axis(along) {}
  template <int D>
  void validate(const Particles<D>& p) const {
    require(axis >= 0 && axis < D, "fixed particles moving along an axis: the axis (" + show(axis) +
                                       ") must be one of the box's");
    FixedParticles::validate(p);
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (int a = 0; a < D; ++a) {
        if (a != axis && p.kind[i] == ParticleKind::fluid && p.velocity[i][a] != 0) {
          throw Error("particle " + show(i) +
                      " starts with a velocity across the axis its motion "
                      "is confined to (" +
                      show(p.velocity[i][a]) + " along " + axis_name(a) + ")");
        }
      }
    }
  }
  /// Keep only the component along the axis.
  template <int D>
  void constrain_acceleration(Vec<D>& a) const {
    const double along = a[axis];
    a.setZero();
    a[axis] = along;
  }
};

}  // namespace sph
