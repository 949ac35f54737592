#pragma once
/// \file
/// \brief Boundaries a scene names: what the integrator may move, and where.
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

#include <cmath>
#include <string>

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

/// A reflecting sphere: the gas is held inside \f$ |\mathbf x - \mathbf c| \le R \f$ by a wall
/// that returns every particle that crosses it as an elastic bounce (Watkins et al. 1996,
/// sect. 4.4: the rotating cloud collapses inside a reflecting sphere).  A particle found
/// outside after a drift is taken back along its straight path (it drifted with the velocity
/// \f$ \mathbf v \f$ the integrator hands over) to the point \f$ \mathbf p \f$ where it crossed
/// the wall, \f$ s \f$ time units ago; its velocity is mirrored in the wall there,
/// \f$ \mathbf v' = \mathbf v - 2(\mathbf v\cdot\hat{\mathbf n})\hat{\mathbf n} \f$, and it
/// moves on for the time \f$ s \f$: \f$ \mathbf x' = \mathbf p + s\,\mathbf v' \f$.  The kick of
/// the wall is radial, so the speed and the angular momentum about the centre are exactly those
/// before the bounce (\f$ \mathbf x'\times\mathbf v' = \mathbf p\times\mathbf v' =
/// \mathbf p\times\mathbf v = \mathbf x\times\mathbf v \f$ about the centre).  A particle that
/// would still be outside after that had a step far too long for the wall: `constrain` leaves
/// it and returns false, and the step stops with a message naming it.
template <int D>
struct ReflectingSphere {
  static constexpr const char* name = "reflecting sphere";
  static constexpr bool has_constraint = true;

  Vec<D> centre = Vec<D>::Zero();
  double radius = 1.0;

  ReflectingSphere() = default;
  ReflectingSphere(const Vec<D>& c, double r) : centre(c), radius(r) {
    require(c.allFinite(), "reflecting sphere: the centre must be finite");
    require(std::isfinite(r) && r > 0,
            "reflecting sphere: the radius must be positive (got " + show(r) + ")");
  }

  static constexpr bool moves(std::size_t, const Particles<D>&) { return true; }
  /// Every particle must start inside the sphere.
  void validate(const Particles<D>& p) const {
    NoBoundaries{}.validate(p);
    for (std::size_t i = 0; i < p.size(); ++i) {
      if ((p.position[i] - centre).norm() > radius) {
        throw Error("reflecting sphere: particle " + show(i) + " at " +
                    to_string<D>(p.position[i]) + " starts outside the sphere of radius " +
                    show(radius));
      }
    }
  }
  /// Bring a particle that has crossed the wall back inside, with its velocity mirrored at the
  /// point where it crossed (false, and nothing changed, when that is not possible).
  bool constrain(Vec<D>& x, Vec<D>& v) const {
    const Vec<D> d = x - centre;
    const double r2 = d.squaredNorm();
    if (r2 <= radius * radius) return true;
    // The time s since the crossing: the smaller root of |d - s v|^2 = R^2 (the path left the
    // sphere moving outwards, d.v > 0).
    const double dv = d.dot(v), vv = v.squaredNorm();
    const double discriminant = dv * dv - vv * (r2 - radius * radius);
    if (!(dv > 0 && discriminant >= 0)) return false;
    const double s = (dv - std::sqrt(discriminant)) / vv;
    const Vec<D> crossing = d - s * v;
    const Vec<D> n = crossing / crossing.norm();
    const Vec<D> mirrored = v - 2 * v.dot(n) * n;
    const Vec<D> back = crossing + s * mirrored;
    if (!(back.squaredNorm() <= radius * radius * (1 + 1e-12))) return false;
    x = centre + back;
    v = mirrored;
    return true;
  }
  /// What went wrong when constrain() returned false.
  std::string describe_failure(const Vec<D>& x) const {
    return "reflecting sphere: the particle at " + to_string<D>(x) +
           " crossed the wall of radius " + show(radius) +
           " and cannot be brought back along its path (the step is far too long for "
           "the wall)";
  }
};

}  // namespace sph
